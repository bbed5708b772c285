// What a public bounce::Scene holds: the internal scene model (src/scene/scene.h).
#pragma once
#include <bounce/scene.h>

#include "scene/scene.h"

namespace bounce::api {

struct Scene::Impl {
  bounce::Scene scene;
};

}  // namespace bounce::api
