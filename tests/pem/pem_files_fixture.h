#pragma once
// A scratch folder for PEM assets on disk (pem_local_asset_test, pem_mip_asset_test,
// probe/pem_runtime_test): the asset's paths, a manifest edit in place, and the reader's
// refusal checked by file and field.
#include "components/reflection_probe/pem/pem_asset.h"
#include "engine/core/error.h"
#include "support/scratch_dir_test.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <functional>
#include <string>

namespace specula::test {

class PemFilesTest : public ScratchDirTest {
protected:
    explicit PemFilesTest(std::string prefix) : ScratchDirTest(std::move(prefix)) {}

    std::string dir() const { return (root_ / "pem").string(); }
    std::string manifest() const { return dir() + "/manifest.json"; }
    std::string file(const std::string& name) const { return dir() + "/" + name; }

    void editManifest(const std::function<void(nlohmann::json&)>& edit) const {
        nlohmann::json m = nlohmann::json::parse(std::ifstream(manifest()));
        edit(m);
        std::ofstream(manifest()) << m.dump(1);
    }
    void expectRefused(const std::string& fileSuffix, const std::string& field) const {
        try {
            readPemProbe(manifest());
            ADD_FAILURE() << "expected " << field << " to be refused";
        } catch (const Error& e) {
            std::printf("refused: %s\n", e.what());
            EXPECT_TRUE(e.file().ends_with(fileSuffix)) << e.what();
            EXPECT_EQ(e.field(), field) << e.what();
        }
    }
};

} // namespace specula::test
