// Where the public types live. They are declared in namespace bounce::api and used as bounce::X
// (the using-directive below): Bounce's own code under src/ has internal types of the same names
// (bounce::Scene, bounce::Camera, ...) that a host never sees, and src/api/, which sees both,
// compiles with BOUNCE_API_IMPLEMENTATION and names the public ones api::X.
#pragma once

namespace bounce::api {}

#ifndef BOUNCE_API_IMPLEMENTATION
namespace bounce {
using namespace api;
}  // namespace bounce
#endif
