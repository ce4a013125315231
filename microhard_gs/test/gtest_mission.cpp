// Mission validation and the lat/lon -> feet-from-home conversion, without any link.
#include <gtest/gtest.h>

#include <cmath>

#include "geo.h"
#include "gs_test_config.h"
#include "mavlink_all.h"
#include "mission.h"
#include "mission_frames.h"

using namespace microhard_gs;

namespace {
const GeoPoint kHome{40.1100, -88.2200, 220.0};

MissionLimits limits() { return test::mission_limits(); }

MissionItem waypoint(uint16_t seq, double north_ft, double east_ft, double height_ft) {
  double lat = 0, lon = 0;
  north_east_ft_to_geodetic(kHome, NorthEastFt{north_ft, east_ft}, &lat, &lon);
  MissionItem it;
  it.seq = seq;
  it.frame = MAV_FRAME_GLOBAL_RELATIVE_ALT_INT;
  it.command = MAV_CMD_NAV_WAYPOINT;
  it.x = static_cast<int32_t>(std::lround(lat * 1e7));
  it.y = static_cast<int32_t>(std::lround(lon * 1e7));
  it.z = static_cast<float>(height_ft / kFeetPerMetre);
  return it;
}
}  // namespace

TEST(Geo, OneArcMinuteNorthIsAboutOneNauticalMile) {
  const NorthEastFt ne =
      geodetic_to_north_east_ft(kHome, kHome.lat_deg + 1.0 / 60.0, kHome.lon_deg);
  EXPECT_NEAR(ne.north_ft, 6076.0, 15.0);  // a nautical mile, give or take the ellipsoid
  EXPECT_NEAR(ne.east_ft, 0.0, 1e-9);
}

TEST(Geo, EastShrinksWithCosineOfLatitude) {
  const NorthEastFt at_home = geodetic_to_north_east_ft(kHome, kHome.lat_deg, kHome.lon_deg + 0.01);
  const GeoPoint equator{0.0001, -88.22, 0.0};
  const NorthEastFt at_equator =
      geodetic_to_north_east_ft(equator, equator.lat_deg, equator.lon_deg + 0.01);
  EXPECT_NEAR(at_home.east_ft / at_equator.east_ft, std::cos(kHome.lat_deg * M_PI / 180.0), 0.002);
}

TEST(Geo, RoundTripIsExactToAnInch) {
  double lat = 0, lon = 0;
  north_east_ft_to_geodetic(kHome, NorthEastFt{-1234.5, 2345.6}, &lat, &lon);
  const NorthEastFt back = geodetic_to_north_east_ft(kHome, lat, lon);
  EXPECT_NEAR(back.north_ft, -1234.5, 0.08);
  EXPECT_NEAR(back.east_ft, 2345.6, 0.08);
}

TEST(Mission, TenWaypointsBecomeAFlightPlanInFeetFromHome) {
  MissionItem items[10];
  for (int i = 0; i < 10; ++i)
    items[i] = waypoint(static_cast<uint16_t>(i), 100.0 * i, -50.0 * i, 150.0 + 10 * i);
  WayPlan plan;
  const MissionVerdict v = build_way_plan(items, 10, kHome, limits(), &plan);
  ASSERT_TRUE(v.ok()) << v.reason;
  ASSERT_EQ(plan.fp, 10);
  EXPECT_NEAR(plan.north_ft[7], 700.0, 0.5);
  EXPECT_NEAR(plan.east_ft[7], -350.0, 0.5);
  EXPECT_NEAR(plan.height_ft[7], 220.0, 0.01);
  EXPECT_DOUBLE_EQ(plan.velocity_ftps[7], 60.0);
}

TEST(Mission, WaypointAt600FtIsRejectedNamingTheCeiling) {
  MissionItem items[2] = {waypoint(0, 0, 0, 200), waypoint(1, 100, 0, 600)};
  WayPlan plan;
  plan.fp = 7;  // stands for the mission already held
  const MissionVerdict v = build_way_plan(items, 2, kHome, limits(), &plan);
  EXPECT_EQ(v.result, MAV_MISSION_INVALID_PARAM7);
  EXPECT_NE(v.reason.find("ceiling"), std::string::npos) << v.reason;
  EXPECT_EQ(plan.fp, 7);  // untouched
}

TEST(Mission, WaypointBelowTheFloorIsRejected) {
  const MissionVerdict v = check_mission_item(waypoint(3, 0, 0, 50), kHome, limits());
  EXPECT_EQ(v.result, MAV_MISSION_INVALID_PARAM7);
  EXPECT_NE(v.reason.find("floor"), std::string::npos);
}

TEST(Mission, WaypointBeyondTheRadiusIsRejected) {
  const MissionVerdict v = check_mission_item(waypoint(0, 2500, 2500, 200), kHome, limits());
  EXPECT_EQ(v.result, MAV_MISSION_INVALID_PARAM5_X);
  EXPECT_NE(v.reason.find("from home"), std::string::npos);
}

TEST(Mission, AmslFrameIsMeasuredFromHomeAltitude) {
  MissionItem it = waypoint(0, 0, 0, 0);
  it.frame = MAV_FRAME_GLOBAL_INT;
  it.z = static_cast<float>(kHome.alt_m + 500.0 / kFeetPerMetre);  // 500 ft above home
  EXPECT_EQ(check_mission_item(it, kHome, limits()).result, MAV_MISSION_INVALID_PARAM7);
  it.z = static_cast<float>(kHome.alt_m + 300.0 / kFeetPerMetre);
  EXPECT_TRUE(check_mission_item(it, kHome, limits()).ok());
}

TEST(Mission, ThirtyThreeItemsDoNotFit) {
  MissionItem items[kMaxMissionItems];
  WayPlan plan;
  EXPECT_EQ(build_way_plan(items, 33, kHome, limits(), &plan).result, MAV_MISSION_NO_SPACE);
}

TEST(Mission, ChangeSpeedAppliesToFollowingLegsAndStallIsRefused) {
  MissionItem speed;
  speed.seq = 1;
  speed.command = MAV_CMD_DO_CHANGE_SPEED;
  speed.frame = MAV_FRAME_MISSION;
  speed.param2 = 25.0f;  // m/s
  MissionItem items[3] = {waypoint(0, 0, 0, 200), speed, waypoint(2, 300, 0, 200)};
  WayPlan plan;
  ASSERT_TRUE(build_way_plan(items, 3, kHome, limits(), &plan).ok());
  ASSERT_EQ(plan.fp, 2);
  EXPECT_DOUBLE_EQ(plan.velocity_ftps[0], 60.0);
  EXPECT_NEAR(plan.velocity_ftps[1], 25.0 * kFeetPerMetre, 1e-4);
  items[1].param2 = 10.0f;  // 33 ft/s, below the 42 ft/s stall
  EXPECT_EQ(build_way_plan(items, 3, kHome, limits(), &plan).result, MAV_MISSION_INVALID_PARAM2);
}

TEST(Mission, TakeoffAndOtherFramesAreUnsupported) {
  MissionItem it = waypoint(0, 0, 0, 200);
  it.command = MAV_CMD_NAV_TAKEOFF;
  EXPECT_EQ(check_mission_item(it, kHome, limits()).result, MAV_MISSION_UNSUPPORTED);
  it = waypoint(0, 0, 0, 200);
  it.frame = MAV_FRAME_LOCAL_NED;
  EXPECT_EQ(check_mission_item(it, kHome, limits()).result, MAV_MISSION_UNSUPPORTED_FRAME);
}

TEST(Mission, NotANumberAltitudeIsRejected) {
  MissionItem it = waypoint(0, 0, 0, 200);
  it.z = NAN;
  EXPECT_EQ(check_mission_item(it, kHome, limits()).result, MAV_MISSION_INVALID_PARAM7);
}

TEST(Mission, EveryGlobalFrameGivesTheSameHeightAboveHome) {
  // 0 and 5 are MSL, measured from home's altitude; 3 and 6 are already above home.
  const uint8_t frames[] = {MAV_FRAME_GLOBAL, MAV_FRAME_GLOBAL_RELATIVE_ALT, MAV_FRAME_GLOBAL_INT,
                            MAV_FRAME_GLOBAL_RELATIVE_ALT_INT};
  for (uint8_t frame : frames) {
    MissionItem it = waypoint(1, 400, 0, 0);
    it.frame = frame;
    const bool absolute = frame == MAV_FRAME_GLOBAL || frame == MAV_FRAME_GLOBAL_INT;
    it.z = static_cast<float>((absolute ? kHome.alt_m : 0.0) + 250.0 / kFeetPerMetre);
    MissionItem items[1] = {it};
    WayPlan plan;
    ASSERT_TRUE(build_way_plan(items, 1, kHome, limits(), &plan).ok()) << int(frame);
    EXPECT_NEAR(plan.height_ft[0], 250.0, 0.01) << int(frame);
    EXPECT_NEAR(plan.north_ft[0], 400.0, 0.5) << int(frame);
  }
}

TEST(Mission, ItemZeroOnTheGroundIsHomeAndIsNotFlown) {
  // A MAVProxy / ArduPilot waypoint file: row 0 is home, MSL, then the waypoints.
  MissionItem home_row = waypoint(0, 0, 0, 0);
  home_row.frame = MAV_FRAME_GLOBAL;
  home_row.z = static_cast<float>(kHome.alt_m);
  MissionItem items[3] = {home_row, waypoint(1, 300, 0, 200), waypoint(2, 600, 100, 250)};
  EXPECT_TRUE(is_home_row(items[0], kHome, limits()));
  WayPlan plan;
  const MissionVerdict v = build_way_plan(items, 3, kHome, limits(), &plan);
  ASSERT_TRUE(v.ok()) << v.reason;
  ASSERT_EQ(plan.fp, 2);
  EXPECT_NEAR(plan.north_ft[0], 300.0, 0.5);
  EXPECT_EQ(plan.item_seq[0], 1);
  EXPECT_EQ(plan.item_seq[1], 2);
}

TEST(Mission, ItemZeroAtFlyingHeightIsTheFirstWaypoint) {
  // QGroundControl with a generic autopilot sends no home: its first waypoint is seq 0.
  MissionItem items[2] = {waypoint(0, 300, 0, 200), waypoint(1, 600, 0, 200)};
  EXPECT_FALSE(is_home_row(items[0], kHome, limits()));
  WayPlan plan;
  ASSERT_TRUE(build_way_plan(items, 2, kHome, limits(), &plan).ok());
  EXPECT_EQ(plan.fp, 2);
  EXPECT_EQ(plan.item_seq[0], 0);
}

TEST(Mission, HomeRowIsStillCheckedAsAPositionAndOnlyAtSeqZero) {
  MissionItem far_home = waypoint(0, 2500, 2500, 0);
  EXPECT_EQ(check_mission_item(far_home, kHome, limits()).result, MAV_MISSION_INVALID_PARAM5_X);
  MissionItem items[2] = {waypoint(0, 0, 0, 0), waypoint(1, 300, 0, 20)};  // row 1 on the ground
  WayPlan plan;
  const MissionVerdict v = build_way_plan(items, 2, kHome, limits(), &plan);
  EXPECT_EQ(v.result, MAV_MISSION_INVALID_PARAM7);
  EXPECT_NE(v.reason.find("Item 1"), std::string::npos) << v.reason;
}

TEST(MissionFrames, LegacyItemKeepsItsFrameAndCarriesDegrees) {
  mavlink_mission_item_t wire{};
  wire.seq = 2;
  wire.frame = MAV_FRAME_GLOBAL_RELATIVE_ALT;
  wire.command = MAV_CMD_NAV_WAYPOINT;
  wire.x = 40.1234567f;
  wire.y = -88.2345678f;
  wire.z = 61.0f;
  const MissionItem it = from_item_float(wire);
  EXPECT_EQ(it.frame, MAV_FRAME_GLOBAL_RELATIVE_ALT);
  EXPECT_NEAR(it.x, 401234567, 30);  // float32 degrees: a few 1e-7 deg
  EXPECT_NEAR(it.y, -882345678, 30);
  const mavlink_mission_item_int_t as_int = to_item_int(it);
  EXPECT_EQ(as_int.frame, MAV_FRAME_GLOBAL_RELATIVE_ALT);
  EXPECT_EQ(as_int.x, it.x);
  const mavlink_mission_item_t back = to_item_float(it);
  EXPECT_EQ(back.frame, MAV_FRAME_GLOBAL_RELATIVE_ALT);
  EXPECT_FLOAT_EQ(back.x, wire.x);
  MissionItem int_frame = it;
  int_frame.frame = MAV_FRAME_GLOBAL_INT;
  EXPECT_EQ(to_item_float(int_frame).frame, MAV_FRAME_GLOBAL);  // degrees travel in the float twin
  EXPECT_EQ(to_item_int(int_frame).frame, MAV_FRAME_GLOBAL_INT);
}

TEST(MissionFrames, NonFiniteLegacyCoordinatesAreRefusedNotWrapped) {
  mavlink_mission_item_t wire{};
  wire.frame = MAV_FRAME_GLOBAL;
  wire.command = MAV_CMD_NAV_WAYPOINT;
  wire.x = NAN;
  wire.y = -88.22f;
  wire.z = 300.0f;
  EXPECT_EQ(check_mission_item(from_item_float(wire), kHome, limits()).result,
            MAV_MISSION_INVALID_PARAM5_X);
}
