#include "probe_setup.h"

#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/image/image_io.h"
#include "engine/scene/components.h"
#include "engine/scene/transform_system.h"

#include <filesystem>

namespace specula {

ProbeScene::ProbeScene(const std::string& gltfPath, const std::string& skyPath) : path(gltfPath) {
    loaded = loadGltf(gltfPath, registry);
    updateWorldTransforms(registry);
    markup = readSceneMarkup(registry, loaded, gltfPath);
    if (!skyPath.empty()) sky = readImage(skyPath);
}

ecs::Entity attachProbeComponents(ecs::Registry& registry, const SceneMarkup& markup,
                                  const ReflectionProbe& probe, ecs::Entity previous) {
    if (!previous.isNull()) registry.destroy(previous);
    const ecs::Entity e = registry.create();
    registry.emplace<Name>(e, Name{"reflection_probe"});
    registry.emplace<ReflectionProbe>(e, probe);
    for (const ReflectorMarkup& r : markup.reflectors)
        for (ecs::Entity mesh : r.meshes)
            registry.emplace<Reflector>(mesh, Reflector{e, r.f0});
    return e;
}

CookedProbeFacts readCookedProbeFacts(const std::string& manifestPath) {
    const nlohmann::json m = parseManifestJson(readManifestText(manifestPath), manifestPath);
    const ManifestFields r{manifestPath};
    CookedProbeFacts f;
    f.flavour = r.probeFlavour(m, kProbeFormatVersion);
    if (m.contains("source")) f.source = r.string(m, "source", "");
    if (m.contains("sky"))
        f.skyFile =
            r.fileInFolder(m["sky"], "sky.", std::filesystem::path(manifestPath).parent_path());
    return f;
}

} // namespace specula
