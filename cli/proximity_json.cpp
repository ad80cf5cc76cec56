// The JSON of proximity answers (proximity_json.hpp).
#include "proximity_json.hpp"

#include "common.hpp"

namespace minksum::cli {

const char* feature_type(FeatureDim dim) {
  return dim == FeatureDim::vertex ? "vertex" : dim == FeatureDim::edge ? "edge" : "facet";
}

std::string feature_json(const Feature& f) {
  return std::string("{\"type\": \"") + feature_type(f.dim) + "\", \"index\": " + std::to_string(f.index) + "}";
}

std::string witness_json(const Witness& w) {
  return "{\"facet\": " + std::to_string(w.facet) + ", \"m\": " + feature_json(w.m) + ", \"p\": " +
         feature_json(w.p) + ", \"q\": " + feature_json(w.q) + "}";
}

std::string exact_vector_json(const Point3& p) {
  return "[\"" + format_exact(p.x) + "\", \"" + format_exact(p.y) + "\", \"" + format_exact(p.z) + "\"]";
}

std::string double_vector_json(const Point3& p) {
  return "[" + json_number(to_double(p.x)) + ", " + json_number(to_double(p.y)) + ", " +
         json_number(to_double(p.z)) + "]";
}

}  // namespace minksum::cli
