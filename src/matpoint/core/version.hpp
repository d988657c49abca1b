#pragma once

namespace matpoint {
inline constexpr const char* kVersion = "0.1.0";
}
