// Test worlds built in code, so a fresh clone has scenes with exact ground
// truth. All are in metres, Z up, resting on z = 0 unless stated.
//   box     a 4 m cube centred at (0, 0, 2)
//   sphere  a sphere of radius 2 m centred at (0, 0, 2)
//   room    a closed 10 x 8 x 4 m room seen from inside (normals inward),
//           x in [-5, 5], y in [-4, 4], z in [0, 4], with a 1 m pillar
//   plant   an industrial plant inside a 65 x 42 x 15 m box: a main hall with
//           walls and a roof, five equal flues, thin gantries, a narrow passage
//   statue  a 20 x 20 x 60 m figure on a pedestal with sharp edges and thin parts
//   multistorey  an open-sided 60 x 40 x 45.6 m parking structure in three
//           terraced tiers: 13 decks 3.3 m apart (3 m clear), ramps, columns,
//           parapets with gaps, two stair cores
#pragma once

#include <string>
#include <vector>

#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// Names accepted by makeProceduralScene, in a stable order.
const std::vector<std::string>& proceduralSceneNames();

bool isProceduralScene(const std::string& name);

// Builds the named scene into `mesh` (replacing its content). Unknown names
// give an error listing the known ones.
Status makeProceduralScene(const std::string& name, TriangleMesh* mesh);

}  // namespace surface_nbv
