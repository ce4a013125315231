"""Seeded fault campaigns of lockstep HiL flights, run on Dask (hil/campaign.py is the front door):
plan.py draws the flights from one campaign seed, flight.py flies one under its own wall-clock
limit, runner.py runs them on a Dask cluster and streams the rows to a CSV, report.py makes the
table, the plots and the HTML page."""
