#include "param_tree.h"

namespace controller {

bool number_at(XmlRpc::XmlRpcValue &tree, const std::string &key, double *value) {
  XmlRpc::XmlRpcValue *node = &tree;
  std::string::size_type from = 0;
  while (true) {
    const std::string::size_type slash = key.find('/', from);
    const std::string part = key.substr(from, slash == std::string::npos ? slash : slash - from);
    // hasMember first: operator[] on a struct adds a missing member.
    if (part.empty() || node->getType() != XmlRpc::XmlRpcValue::TypeStruct ||
        !node->hasMember(part)) {
      return false;
    }
    node = &(*node)[part];
    if (slash == std::string::npos) {
      break;
    }
    from = slash + 1;
  }
  switch (node->getType()) {
    case XmlRpc::XmlRpcValue::TypeDouble:
      *value = static_cast<double>(*node);
      return true;
    case XmlRpc::XmlRpcValue::TypeInt:
      *value = static_cast<int>(*node);
      return true;
    case XmlRpc::XmlRpcValue::TypeBoolean:
      *value = static_cast<bool>(*node) ? 1.0 : 0.0;
      return true;
    default:
      return false;
  }
}

}  // namespace controller
