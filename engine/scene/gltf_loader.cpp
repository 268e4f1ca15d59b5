// The loader's entry point: container and JSON pre-pass, tinygltf with file access of our
// own, then conversion. The steps live in the gltf_*.cpp files beside this one.
#include "gltf_loader.h"

#include "engine/core/error.h"
#include "engine/core/regular_file.h"
#include "engine/scene/gltf_container.h"
#include "engine/scene/gltf_context.h"
#include "engine/scene/gltf_convert.h"
#include "engine/scene/gltf_prepass.h"
#include "engine/scene/tinygltf_config.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <optional>

namespace specula {

namespace {

namespace fs = std::filesystem;
using namespace gltf_internal;

// tinygltf's own file callbacks open whatever a URI names: a directory (URI ".") reads as
// SIZE_MAX bytes (std::bad_alloc), a FIFO blocks and /dev/zero never ends. These accept
// regular files only, bounded; a refusal reaches the loader as tinygltf's error or warning,
// with the reason.
bool gltfFileExists(const std::string& path, void*) {
    std::error_code ec;
    return fs::symlink_status(path, ec).type() != fs::file_type::not_found && !ec;
}
std::string gltfExpandFilePath(const std::string& path, void*) {
    return path; // no ~ or $VAR expansion: a URI is a path relative to the glTF
}
bool gltfReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                       void*) {
    try {
        *out = readRegularFile<std::vector<unsigned char>>(path, kMaxGltfFileBytes);
        return true;
    } catch (const Error& e) {
        if (err) *err += e.what();
        return false;
    }
}
bool gltfRefuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&,
                     void*) {
    if (err) *err += "the loader never writes files";
    return false;
}

// Keeps images encoded: bufferView images are decoded later, after the loader has checked
// the view's range (tinygltf passes an unchecked pointer here), and only the images a
// material actually uses get decoded at all.
bool keepImageEncoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    image->as_is = true;
    if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

// What tinygltf is handed: the JSON text, and for a GLB the container bytes around it
// (rebuilt when the pre-pass changed the JSON).
struct TinygltfInput {
    bool glb = false;
    std::string json;
    std::vector<unsigned char> rebuilt;
    const unsigned char* glbBytes = nullptr;
    std::size_t glbSize = 0;
};

TinygltfInput prepareInput(const std::string& path, const std::vector<unsigned char>& bytes) {
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });

    TinygltfInput in;
    std::optional<GlbLayout> glb;
    if (binary || ext == ".glb") {
        glb = validateGlb(path, bytes);
        in.json.assign(reinterpret_cast<const char*>(glb->json), glb->jsonSize);
    } else {
        in.json.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    }
    const std::optional<std::string> rewritten = precheck(path, in.json, glb ? &*glb : nullptr);
    in.glb = glb.has_value();
    in.glbBytes = bytes.data();
    in.glbSize = glb ? glb->length : 0;
    if (rewritten) {
        in.json = *rewritten;
        if (glb) {
            in.rebuilt = rebuildGlb(bytes, *glb, in.json);
            in.glbBytes = in.rebuilt.data();
            in.glbSize = in.rebuilt.size();
        }
    }
    return in;
}

tinygltf::Model parse(const std::string& path, const TinygltfInput& in, std::string& warn) {
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&gltfFileExists, &gltfExpandFilePath,
                                                &gltfReadWholeFile, &gltfRefuseWrite, nullptr});
    loader.SetImageLoader(&keepImageEncoded, nullptr);
    loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
    tinygltf::Model model;
    std::string err;
    const std::string baseDir = fs::path(path).parent_path().string();
    bool ok = false;
    try {
        if (in.glb)
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, in.glbBytes,
                                             static_cast<unsigned int>(in.glbSize), baseDir);
        else
            ok = loader.LoadASCIIFromString(&model, &err, &warn, in.json.data(),
                                            static_cast<unsigned int>(in.json.size()), baseDir);
    } catch (const std::exception& e) {
        throw Error(path, "", std::string("glTF parse failed: ") + oneLine(e.what()));
    }
    if (!ok) {
        const std::string why = oneLine(err);
        throw Error(path, "", "glTF parse failed: " + (why.empty() ? "unknown reason" : why));
    }
    return model;
}

} // namespace

LoadedScene loadGltf(const std::string& path, ecs::Registry& registry) {
    const std::vector<unsigned char> bytes = readWholeFile(path);
    const TinygltfInput in = prepareInput(path, bytes);
    std::string warn;
    const tinygltf::Model model = parse(path, in, warn);

    LoadedScene scene;
    if (const std::string w = oneLine(warn); !w.empty()) scene.warnings.push_back("tinygltf: " + w);
    gltf_internal::convertScene(path, model, scene, registry);
    return scene;
}

} // namespace specula
