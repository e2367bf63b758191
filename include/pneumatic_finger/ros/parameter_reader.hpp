// Every node's parameters, read one way: a table that defines each (type, default, unit, range, meaning) and one
// reader of the private handle. A number is checked by the core's checkParameterValue, the same rule and message as
// the actuator's keys in a YAML file, so the finger node, the gripper action server, the regulator and the sequencer
// refuse a bad value alike. `NODE --parameters` prints the table, from which docs/ are generated.
#pragma once

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

/// One node parameter: its one definition.
struct NodeParameterSpec {
  std::string key;
  std::string type;          ///< "string", "double", "int", "bool", "double[3]", "double[]", "string[]"
  std::string default_text;  ///< the default as the docs show it ("required" when there is none)
  double default_value;      ///< the default of a number or a bool (1 = true)
  double min_value;          ///< range of a number (of every entry of a "double[3]": |x| <= max_value)
  bool min_open;             ///< whether min_value itself is excluded
  double max_value;
  std::string unit;
  std::string allowed;  ///< the range as text (the core's describeRange for numbers)
  std::string description;
};

/// Table rows: a number in a range, a whole number, text, a flag, three numbers |x| <= limit, and a required list.
NodeParameterSpec numberParameter(const char* key, double def, double lo, bool lo_open, double hi, const char* unit,
                                  const char* description, const char* allowed = nullptr);
/// A number the core defines (a key of the parameter file that the node also reads): its default, unit and range
/// are the core's; @p node_use adds what the node does with it to the core's description.
NodeParameterSpec coreNumberParameter(const ParameterSpec& core, const char* node_use, const char* allowed = nullptr);
NodeParameterSpec integerParameter(const char* key, int def, int lo, int hi, const char* description);
NodeParameterSpec textParameter(const char* key, const std::string& def, const char* allowed, const char* description);
NodeParameterSpec flagParameter(const char* key, bool def, const char* description);
NodeParameterSpec tripleParameter(const char* key, double limit, const char* unit, const char* limit_text,
                                  const char* description);
NodeParameterSpec listParameter(const char* key, const char* type, const char* unit, const char* allowed,
                                const char* description);

/// A value as a message shows it: numbers with every digit, lists as [a, b, c], text in quotes.
std::string describeParameterValue(const XmlRpc::XmlRpcValue& v);

/// A number (a double, an int, or a string that is one whole number: rosparam reads "1e-05" as a string) as @p out;
/// false for anything else.
bool asParameterNumber(const XmlRpc::XmlRpcValue& v, double& out);

/// A parameter server value (a namespace: a struct) as the YAML tree a parameter file parses to: numbers keep every
/// bit, text stays text (the core reads "1e-05" as the number rosparam's YAML 1.1 took for a string).
YAML::Node parameterTree(const XmlRpc::XmlRpcValue& v);

/// The entries of a list value as numbers. @throws ParameterError naming the key, the value and the entry
std::vector<double> parameterNumbers(const XmlRpc::XmlRpcValue& v, const std::string& key);

/// The one range check of a node number (at start-up and for a value from elsewhere, dynamic_reconfigure): the
/// core's checkParameterValue; @p max_override replaces the table's upper bound. Returns @p x when it is allowed.
double checkNumberParameter(const NodeParameterSpec& spec, double x, double max_override = NAN);

/// The reader of one node's private handle against its table. Absent keys take the table's default; every
/// read value is checked. Every method throws ParameterError naming the key, the value and what is allowed.
class NodeParameterReader {
 public:
  NodeParameterReader(const ros::NodeHandle& nh, const std::vector<NodeParameterSpec>& specs);

  const NodeParameterSpec& spec(const std::string& key) const;
  const ros::NodeHandle& handle() const { return nh_; }
  /// A number (a "double" or an "int"); @p max_override replaces the table's upper bound (a bound set by another key).
  double number(const std::string& key, double max_override = NAN) const;
  bool flag(const std::string& key) const;
  std::string text(const std::string& key) const;
  /// Text that must be a valid ROS name (a topic, a parameter).
  std::string rosName(const std::string& key) const;
  std::array<double, 3> triple(const std::string& key) const;
  /// A required list of numbers; of exactly @p size entries unless it is 0.
  std::vector<double> numbers(const std::string& key, std::size_t size = 0) const;
  /// A required, non-empty list of non-empty strings.
  std::vector<std::string> texts(const std::string& key) const;
  /// The keys set in the handle's namespace, relative to it (nested ones as "ns/key").
  std::vector<std::string> givenKeys() const;
  /// Refuses a key in the handle's namespace that is neither in the table nor accepted by @p also_known: a typo is
  /// an error, not a silent default. Nested namespaces belong to others (diagnostics) and are left alone.
  template <class Known>
  void refuseUnknownKeys(Known also_known) const {
    for (const std::string& key : givenKeys()) {
      if (key.find('/') == std::string::npos && findSpec(key) == nullptr && !also_known(key)) {
        throw ParameterError("unknown parameter '" + key + "' (in " + nh_.getNamespace() + "/)");
      }
    }
  }
  void refuseUnknownKeys() const {
    refuseUnknownKeys([](const std::string&) { return false; });
  }

 private:
  const NodeParameterSpec* findSpec(const std::string& key) const;

  const ros::NodeHandle& nh_;
  const std::vector<NodeParameterSpec>& specs_;
};

/// The table as Markdown (`NODE --parameters`, from which docs/ are generated).
std::string parameterTableMarkdown(const std::vector<NodeParameterSpec>& specs);

/// For a node's main: prints the table and returns true when argv[1] is "--parameters".
bool printParametersIfAsked(int argc, char** argv, const std::vector<NodeParameterSpec>& specs);

}  // namespace pneumatic_finger
