// A test fixture with a folder of its own for the files a test writes, and a file's bytes.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace photon::test {

// A file's bytes, all of them ("" for a file that cannot be read).
inline std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// The folder is made before each test and removed after it; its name carries the process id, so
// two test programs running at once do not share one.
class TempFolderTest : public ::testing::Test {
protected:
    explicit TempFolderTest(const std::string& prefix)
        : folder(std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()))) {}

    void SetUp() override { std::filesystem::create_directories(folder); }
    void TearDown() override { std::filesystem::remove_all(folder); }

    std::string path(const std::string& name) const { return (folder / name).string(); }

    std::filesystem::path folder;
};

}  // namespace photon::test
