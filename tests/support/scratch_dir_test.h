#pragma once
// A test fixture with a fresh folder per test: temp/<prefix>-<test name>-<pid>, holding an
// empty "scratch" subfolder to run tools in; removed after the test.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

namespace specula::test {

class ScratchDirTest : public ::testing::Test {
protected:
    explicit ScratchDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = std::filesystem::temp_directory_path() /
                (prefix_ + "-" + info->name() + "-" + std::to_string(::getpid()));
        std::filesystem::remove_all(root_);
        std::filesystem::create_directories(root_ / "scratch");
    }
    void TearDown() override { std::filesystem::remove_all(root_); }

    std::filesystem::path root_;

private:
    std::string prefix_;
};

} // namespace specula::test
