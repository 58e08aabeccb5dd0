// The key tables of a scene file (common/key_table.h): SceneKeys for its
// [sample], [material], [numerics] and [output] tables, StageKeys for its
// [[stage]] tables (with [stage.stop], [stage.asymptote], [stage.rate] and
// [stage.control]). Scene::Parse reads through them; `granasym keys scene`
// and `granasym keys stage` print them.
#pragma once

#include "common/key_table.h"

namespace granasym::dem {

const KeyTable& SceneKeys();
const KeyTable& StageKeys();

}  // namespace granasym::dem
