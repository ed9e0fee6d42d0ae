#pragma once
// The reference config: every key of the config YAML at its default, each with a comment of what
// it does, its range and unit, made from the sections' setting tables. `irlocd --print-config`
// prints it; docs/config.md holds it (a test keeps them equal).

#include <string>

namespace irloc::io {

// The text of a complete config in mode on_robot. Keys without a default (the files, the mount,
// robot.dof) show an example marked "required". Alternatives and the keys of mode outside_in are
// lines commented out as "# key: value", so removing the "# " gives a key the reader takes.
std::string reference_config_yaml();

}  // namespace irloc::io
