// libFuzzer target: the cooked light-field manifest parser (ParsedManifest::parse,
// readLightFieldProbe) on arbitrary text. The manifest "lives" in a folder this target fills at
// start-up with the slab files of the synthetic probe (tests/fuzz/synthetic_lightfield.h), RGB8 and
// BC1 side by side; the bytes are the same every run, so the seed manifests' checksums match and
// inputs that keep a slab's file name and checksum reach the slab reader and the BC1 check. Any
// specula::Error is the expected refusal; anything else is a finding.
//   SPECULA_FUZZ_WRITE_SEEDS=DIR: also writes the two cooked manifests to DIR as seeds (how
//   tests/fuzz/corpus/lightfield/ was made).
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "components/reflection_probe/lightfield/writer/lightfield_probe_writer.h"
#include "engine/core/error.h"
#include "tests/fuzz/synthetic_lightfield.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

fs::path makeProbeFolder() {
    const fs::path root =
        fs::temp_directory_path() / ("specula-fuzz-lf-" + std::to_string(::getpid()));
    fs::remove_all(root);
    const fs::path probe = root / "probe";
    const char* seeds = std::getenv("SPECULA_FUZZ_WRITE_SEEDS");
    for (const auto c :
         {specula::LightFieldCompression::None, specula::LightFieldCompression::BC1}) {
        const fs::path cooked = root / specula::toString(c);
        specula::writeLightFieldProbe(specula::test::smallLightField(c), cooked.string(),
                                      "synthetic");
        fs::create_directories(probe);
        for (const auto& e : fs::directory_iterator(cooked)) {
            const bool manifest = e.path().filename() == "manifest.json";
            if (manifest && seeds)
                fs::copy_file(e.path(),
                              fs::path(seeds) /
                                  (std::string("cooked_") + specula::toString(c) + ".json"),
                              fs::copy_options::overwrite_existing);
            if (!manifest) fs::copy_file(e.path(), probe / e.path().filename());
        }
    }
    return probe;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const fs::path probe = makeProbeFolder();
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const auto parsed =
            specula::ParsedManifest::parse(text, (probe / "manifest.json").string());
        (void)specula::readLightFieldProbe(parsed.view());
    } catch (const specula::Error&) {
    }
    return 0;
}
