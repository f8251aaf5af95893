#pragma once

#include <string_view>

namespace geodual {

/// geodual's release, "MAJOR.MINOR.PATCH": CMake's project(VERSION).
std::string_view version();

/// The release and, where the build had git, the commit it was built from
/// (`git describe --always --dirty`, read at every build), e.g.
/// "0.1.0 (a59dea5-dirty)". Printed by
/// --version and written into glTF asset.generator and the JSON reports.
std::string_view build_version();

}  // namespace geodual
