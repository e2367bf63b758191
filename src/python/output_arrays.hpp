// The arrays a Python call writes: only the outputs asked for, either the caller's (out=, checked: dtype, shape,
// C order, writeable, no memory shared with another or with the input) or fresh ones (numpy's empty(), not
// zero-filled). Internal header of the Python module (src/python).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "pneumatic_finger/core/chord_angle.hpp"
#include "pneumatic_finger/core/evaluation.hpp"

namespace pneumatic_finger_python {

namespace py = pybind11;

enum class Element { kFloat64, kCode, kFlag };  // float64, uint8 (a status code), bool

inline py::dtype dtypeOf(Element e) {
  return e == Element::kFloat64 ? py::dtype::of<double>()
         : e == Element::kCode  ? py::dtype::of<std::uint8_t>()
                                : py::dtype::of<bool>();
}

struct OutputField {
  const char* name;
  Element element;
  std::vector<int> trailing;
};

inline std::string shapeText(const std::vector<py::ssize_t>& shape) {
  std::string out = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) out += (i ? ", " : "") + std::to_string(shape[i]);
  return out + (shape.size() == 1 ? ",)" : ")");
}

// The arrays of a call: the caller's (out=, checked) or fresh ones (numpy's, not zero-filled), only for the outputs
// asked for. outputs None: every field, or with out= exactly out's keys.
class OutputArrays {
 public:
  OutputArrays(const std::vector<OutputField>& fields, const py::object& outputs, const py::object& out,
               py::ssize_t count, py::ssize_t chambers)
      : fields_(fields) {
    if (!out.is_none() && !py::isinstance<py::dict>(out)) throw py::value_error("out must be a dict of numpy arrays");
    const py::dict given = out.is_none() ? py::dict() : out.cast<py::dict>();
    for (const std::string& name : requested(outputs, given)) {
      const OutputField& f = field(name);
      std::vector<py::ssize_t> shape = {count};
      for (int t : f.trailing) shape.push_back(t == -1 ? chambers : t == -2 ? chambers + 2 : t);
      arrays_[name] = given.contains(name) ? checked(f, given[name.c_str()], shape) : fresh(f, shape);
    }
    for (const auto& item : given) {
      const std::string key = py::str(item.first);
      if (!arrays_.count(key)) throw py::value_error("out['" + key + "']: not among the outputs asked for");
    }
  }

  /// The array of @p name, or null when it was not asked for.
  template <class T>
  T* data(const char* name) {
    const auto it = arrays_.find(name);
    return it == arrays_.end() ? nullptr : static_cast<T*>(it->second.mutable_data());
  }

  /// The overlap of any two arrays, or of one with the input, refused: the core would read what it writes.
  void refuseOverlap(const void* input, std::size_t input_bytes) const {
    std::vector<std::pair<const char*, std::pair<const char*, const char*>>> ranges;
    const char* in = static_cast<const char*>(input);
    ranges.push_back({"gauge_pa", {in, in + input_bytes}});
    for (const auto& [name, a] : arrays_) {
      const char* begin = static_cast<const char*>(a.data());
      ranges.push_back({name.c_str(), {begin, begin + a.nbytes()}});
    }
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      for (std::size_t j = i + 1; j < ranges.size(); ++j) {
        const auto& a = ranges[i].second;
        const auto& b = ranges[j].second;
        if (a.first < a.second && b.first < b.second && a.first < b.second && b.first < a.second) {
          throw py::value_error(std::string("out: '") + ranges[j].first + "' shares memory with '" + ranges[i].first +
                                "'");
        }
      }
    }
  }

  /// The result: each array, or for a scalar call its one row (numpy's scalar or array; a status stays a code, as
  /// in an array, and STATUS or CONTACT_STATUS names it).
  py::dict result(bool scalar) const {
    py::dict d;
    for (const auto& [name, a] : arrays_) d[name.c_str()] = scalar ? py::object(a[py::int_(0)]) : py::object(a);
    return d;
  }

 private:
  const OutputField& field(const std::string& name) const {
    for (const OutputField& f : fields_) {
      if (name == f.name) return f;
    }
    std::string known;
    for (const OutputField& f : fields_) known += (known.empty() ? "" : ", ") + std::string(f.name);
    throw py::value_error("unknown output '" + name + "' (known: " + known + ")");
  }

  std::vector<std::string> requested(const py::object& outputs, const py::dict& given) const {
    std::vector<std::string> names;
    if (outputs.is_none() && given.size() > 0) {
      for (const auto& item : given) names.push_back(py::str(item.first));
    } else if (outputs.is_none()) {
      for (const OutputField& f : fields_) names.push_back(f.name);
    } else if (py::isinstance<py::str>(outputs)) {
      throw py::value_error("outputs must be a sequence of names, e.g. ['tip_angle_rad'], not a string");
    } else {
      for (const py::handle& h : outputs) {
        if (!py::isinstance<py::str>(h)) throw py::value_error("outputs must be names (strings)");
        names.push_back(h.cast<std::string>());
      }
    }
    for (const std::string& name : names) field(name);  // an unknown name is refused
    return names;
  }

  static py::array fresh(const OutputField& f, const std::vector<py::ssize_t>& shape) {
    return py::array(dtypeOf(f.element), shape);  // numpy's empty(): not zero-filled
  }

  static py::array checked(const OutputField& f, const py::handle& given, const std::vector<py::ssize_t>& shape) {
    const std::string where = std::string("out['") + f.name + "']: ";
    const std::string wanted = std::string(py::str(dtypeOf(f.element))) + " array of shape " + shapeText(shape);
    if (!py::isinstance<py::array>(given)) throw py::value_error(where + "expected a numpy " + wanted);
    const py::array a = py::reinterpret_borrow<py::array>(given);
    const bool dtype_ok = a.dtype().is(dtypeOf(f.element));
    const std::vector<py::ssize_t> got(a.shape(), a.shape() + a.ndim());
    if (!dtype_ok || got != shape) {
      throw py::value_error(where + "expected a " + wanted + ", got " + std::string(py::str(a.dtype())) + " of shape " +
                            shapeText(got));
    }
    if (!(a.flags() & py::array::c_style)) throw py::value_error(where + "must be C-contiguous");
    if (!a.writeable()) throw py::value_error(where + "must be writeable");
    return a;
  }

  const std::vector<OutputField>& fields_;
  std::map<std::string, py::array> arrays_;
};

// Where the core's batch writes: the arrays of the state's outputs asked for (nullptr for the others).
inline pneumatic_finger::BatchOutputs stateRows(OutputArrays& arrays) {
  pneumatic_finger::BatchOutputs rows;
  rows.stretch = arrays.data<double>("stretch");
  rows.bulge_m = arrays.data<double>("bulge_m");
  rows.half_angle_rad = arrays.data<double>("half_angle_rad");
  rows.joint_angle_rad = arrays.data<double>("joint_angle_rad");
  rows.backbone_m = arrays.data<double>("backbone_m");
  rows.tip_angle_rad = arrays.data<double>("tip_angle_rad");
  rows.status = arrays.data<std::uint8_t>("status");
  return rows;
}

// The chord angle (chord_angle.hpp), when asked for, from each row's tip and tip angle: the batch writes them, into
// a scratch where the caller did not ask for them: a ChordScratch before the batch, writeChord after it.
struct ChordScratch {
  std::vector<double> backbone_m, tip_angle_rad;

  // prepareChord: where the batch writes what the chord needs.
  ChordScratch(OutputArrays& arrays, pneumatic_finger::BatchOutputs& rows, std::size_t count, int chamber_count) {
    if (!arrays.data<double>("chord_angle_rad")) return;
    if (!rows.backbone_m) {
      backbone_m.resize(count * static_cast<std::size_t>(chamber_count + 2) * 2);
      rows.backbone_m = backbone_m.data();
    }
    if (!rows.tip_angle_rad) {
      tip_angle_rad.resize(count);
      rows.tip_angle_rad = tip_angle_rad.data();
    }
  }
};

inline void writeChord(OutputArrays& arrays, const pneumatic_finger::BatchOutputs& rows, std::size_t count,
                       int chamber_count) {
  double* chord = arrays.data<double>("chord_angle_rad");
  const auto points = static_cast<std::size_t>(chamber_count + 2);
  for (std::size_t i = 0; chord && i < count; ++i) {
    const double* tip = rows.backbone_m + (i * points + points - 1) * 2;
    chord[i] = pneumatic_finger::chordAngleRad(tip[0], tip[1], rows.tip_angle_rad[i]);
  }
}

}  // namespace pneumatic_finger_python
