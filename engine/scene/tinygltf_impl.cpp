// The one translation unit that compiles tinygltf's implementation. Everything else
// includes tinygltf_config.h, which fixes the configuration macros for all users.
#define TINYGLTF_IMPLEMENTATION
#include "engine/scene/tinygltf_config.h"
