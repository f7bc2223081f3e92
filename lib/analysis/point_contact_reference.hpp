#pragma once
// The 3D Hertz references of a deck (output.reference types hertz_sphere_plane
// and hertz_two_spheres) and this run's errors against them (results.md
// /reference/<pair>): the analytic radial curve, stored along one in-plane line
// through the contact centre, and the radial errors (analytic/radial_pressure_errors.hpp)
// of the post-processed and Gauss-point pressures over REFERENCE coordinates.
//
// Contact centre and plane: against a rigid plane, the point of the deformable
// face that is lowest along the plane's normal (sampled on a grid of every knot
// span, span ends included, so a lowest point at a corner or knot is exact), and
// the plane's normal; between two faces, the midpoint of their closest sampled
// pair of points and the normal of the second face there.

#include "analysis/scene.hpp"
#include "io/deck.hpp"
#include "io/results_data.hpp"

namespace iga::analysis {

/// The reference data of a 3D point-contact reference; `step` (may be null) is the
/// last converged increment whose errors are measured.
io::ReferenceData point_contact_reference(const Scene& scene, const PairModel& model,
                                          const io::StepData* step);

}  // namespace iga::analysis
