#pragma once
// Reading NURBS patches from a G+Smo XML file (the format of G+Smo's gsFileData,
// as in its filedata/ folder): the geometry of a multi-patch body
// (docs/deck.md, "Multi-patch bodies and named surfaces").
//
// Supported subset, under the root element <xml>:
//   <Geometry type="TensorBSpline2|TensorBSpline3" id="i">
//     <Basis type="TensorBSplineBasis2|3">
//       <Basis type="BSplineBasis" index="k"><KnotVector degree="p">knots</KnotVector></Basis>  (one per direction)
//     </Basis>
//     <coefs geoDim="d">x y (z) per control point</coefs>
//   </Geometry>
//   <Geometry type="TensorNurbs2|TensorNurbs3" id="i">: the same, with the tensor
//     B-spline basis wrapped in <Basis type="TensorNurbsBasis2|3"> next to
//     <weights>one per control point</weights>;
//   <MultiPatch parDim="2|3"><patches type="id_range">first last</patches> or
//     <patches type="id_index">id id ...</patches>, and <interfaces>, <boundary>
//     (read past: the body's topology is re-derived from the control points).
// The patches are the MultiPatch's, in its order, when the file has one; else
// every top-level <Geometry>, in file order. Coefficients are Cartesian and run
// with the first parameter fastest, as io::NurbsData's rows do. A file's geoDim
// may exceed the deck's dimension when the extra coordinates are all zero (a
// planar surface stored in 3D).
//
// Every problem is a DeckError located in the XML file:
// "four.xml:12: error: Geometry(id=3).coefs = abc: not a number" (line only;
// problems of the file as a whole carry no line).

#include "io/deck.hpp"

#include <string>
#include <vector>

namespace iga::io {

struct ImportedPatch {
    std::string name;  ///< "p<id>" (the Geometry's id; its position in the file when it has none)
    NurbsData nurbs;   ///< degrees, knots, control points rows [x, y, (z,) w]
    int line = 0;      ///< line of the <Geometry> element in the XML file
};

/// The patches of the G+Smo XML file at `path` for a `dimension`-D deck (2 or 3).
/// Throws DeckError listing every problem found, located at `path`:line.
std::vector<ImportedPatch> read_gismo_xml(const std::string& path, int dimension);

}  // namespace iga::io
