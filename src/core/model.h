// The scene compiled once: the Scene as written (every field checked against its range) and the Setup it
// resolves to (the relations between keys checked). A command compiles its scene at the edge, once, and hands
// the Model to every layer below it (the simulation, the pictures, the metadata); nothing below the edge
// resolves a scene again (MuJoCo's mjSpec compiled to an mjModel).
#pragma once

#include <string>
#include <vector>

#include "core/scene.h"
#include "core/setup.h"

namespace core {

struct Model {
  Scene scene;  // as written: what the metadata records and --set changed
  Setup setup;  // what the simulation builds
};

// Checks every field and the relations between them (core::validate) and resolves the scene, once. Throws
// core::InputError naming FILE:LINE, the key, the value and what is allowed.
Model compile(const Scene& scene);

// What a compiled scene was given that does nothing in it, one sentence each naming the key, where it was set
// and why: an obstacle's keys with no obstacle, a kick's with no kicks, a vibration's with no vibration, a
// species whose fraction rounds to no grains. Commands print them as warnings; the scene still runs.
std::vector<std::string> ineffective_keys(const Model& m);

}  // namespace core
