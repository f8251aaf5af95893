#include "geodual/pipeline/version.hpp"

namespace geodual {

std::string_view version() { return "0.1.0"; }

}  // namespace geodual
