// Host memory for large arrays: ZeroedMemory is zero, aligned, writable and movable, for small
// arrays (calloc) and large (mapped); huge-page advice leaves memory as it was.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "core/system/host_memory.h"

namespace photon {
namespace {

bool allZero(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {
        if (p[i] != 0) {
            return false;
        }
    }
    return true;
}

TEST(HostMemory, ZeroedMemorySmallAndLargeArraysAreZeroAlignedAndWritable) {
    for (std::size_t bytes : {std::size_t(16), std::size_t(4096), (std::size_t(2) << 20) - 16, std::size_t(2) << 20,
                              (std::size_t(5) << 20) + 48}) {
        ZeroedMemory m(bytes);
        ASSERT_NE(m.data(), nullptr) << bytes;
        EXPECT_EQ(m.bytes(), bytes);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(m.data()) % 16, 0u) << bytes;
        EXPECT_TRUE(allZero(m.data(), bytes)) << bytes;
        std::memset(m.data(), 0xab, bytes);
        EXPECT_EQ(static_cast<unsigned char*>(m.data())[bytes - 1], 0xab);
    }
}

TEST(HostMemory, ZeroedMemoryEmptyHasNoData) {
    ZeroedMemory m(0);
    EXPECT_EQ(m.data(), nullptr);
    EXPECT_EQ(m.bytes(), 0u);
}

TEST(HostMemory, ZeroedMemoryMovesOwnership) {
    ZeroedMemory a(std::size_t(3) << 20);
    void* data = a.data();
    ZeroedMemory b(std::move(a));
    EXPECT_EQ(b.data(), data);
    EXPECT_EQ(a.data(), nullptr);
    EXPECT_EQ(a.bytes(), 0u);
    ZeroedMemory c(64);
    c = std::move(b);
    EXPECT_EQ(c.data(), data);
    EXPECT_EQ(c.bytes(), std::size_t(3) << 20);
    c = ZeroedMemory(32);  // the mapping is released, calloc's memory taken
    EXPECT_EQ(c.bytes(), 32u);
    EXPECT_TRUE(allZero(c.data(), 32));
}

TEST(HostMemory, HugePageAdviceKeepsContents) {
    std::vector<std::uint32_t> v;
    v.reserve(std::size_t(3) << 20);
    adviseHugePages(v.data(), v.capacity() * sizeof(std::uint32_t));
    for (std::uint32_t i = 0; i < (3u << 20); ++i) {
        v.push_back(i * 2654435761u);
    }
    adviseHugePages(v.data() + 1, 100);      // small and unaligned: nothing
    adviseHugePages(v.data() + 3, v.size() * sizeof(std::uint32_t) - 12);  // unaligned within
    adviseHugePages(nullptr, std::size_t(8) << 20);
    for (std::uint32_t i = 0; i < (3u << 20); ++i) {
        ASSERT_EQ(v[i], i * 2654435761u) << i;
    }
}

}  // namespace
}  // namespace photon
