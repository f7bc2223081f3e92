#pragma once
// Validity of an open knot vector as a deck or an imported geometry file gives
// it, shared by the YAML deck reader (body_reader.cpp) and the G+Smo XML reader
// (gismo_xml.cpp) so both report the same problems in the same words.
//
// An open knot vector of degree p: non-decreasing, at least 2(p+1) values, the
// first and the last value each repeated exactly p+1 times around a parameter
// interval of positive length, no interior value repeated more than p times.
// The caller locates each problem: `knot` is the index of the offending value,
// or nullopt when the problem concerns the vector as a whole.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace iga::io {

struct KnotProblem {
    std::optional<std::size_t> knot;  ///< index of the offending value; nullopt: the whole vector
    std::string reason;
};

/// Every problem of `knots` as an open knot vector of degree `degree` (>= 1), in
/// order; empty when it is valid. Stops at the first problem that makes the
/// later checks meaningless (decreasing values, too few values, not open).
std::vector<KnotProblem> knot_vector_problems(const std::vector<double>& knots, int degree);

}  // namespace iga::io
