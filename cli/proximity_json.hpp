// The JSON of proximity answers, shared by 'minksum query' and 'minksum play'
// (the same fields, so that the two can be compared exactly).
#pragma once

#include <minksum/proximity.hpp>

#include <string>

namespace minksum::cli {

// "vertex", "edge" or "facet".
const char* feature_type(FeatureDim dim);
// {"type": "edge", "index": 3}
std::string feature_json(const Feature& f);
// {"facet": F, "m": feature, "p": feature, "q": feature}
std::string witness_json(const Witness& w);
// ["x", "y", "z"]: the exact coordinates as strings.
std::string exact_vector_json(const Point3& p);
// [x, y, z]: their nearest doubles.
std::string double_vector_json(const Point3& p);

}  // namespace minksum::cli
