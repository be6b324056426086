// History variables of a material: named per-point state that a block stores next to its stress.
//
// A material declares its fields once (name, number of components, whether they form a symmetric
// tensor). The element block holds one array per field, `components` values per stress point in
// the same point-major order as `stress` (struct of arrays over fields). Everything that must
// carry a block's state (restart dumps, part switching freeze/restore, VTU frames, later MPI
// packing) loops over these arrays by name without knowing which material wrote them.
#pragma once

#include <string_view>
#include <vector>

namespace rf::material {

struct HistoryField {
  std::string_view name;  // also the restart dataset and the VTU cell array name
  int components = 1;
  // Six components in the Voigt order of the stress (xx, yy, zz, xy, yz, zx) that turn with the
  // material like the stress does (a rigid rotation Q maps a -> Q a Q^T).
  bool symmetric_tensor = false;
};

struct HistoryArray {
  HistoryField field;
  std::vector<double> values;  // field.components per stress point, point-major
};

}  // namespace rf::material
