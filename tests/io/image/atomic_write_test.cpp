// Tests of io/image/atomic_write: output appears complete or not at all, and a failed write leaves
// the previous file and no temporary behind. (Tests run as root, so permission bits cannot be used
// to make a write fail; failures are made with a missing directory, a directory as the target, and
// a writer that throws halfway.)
#include "io/image/atomic_write.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "io/image/image_io.h"
#include "io/image/temp_dir.h"

namespace phos::io {
namespace {

using test::TempDir;

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void put(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

int entries(const std::string& dir) {
    int n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
    return n;
}

Image small_image() {
    Image img(3, 2);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = Rgb(float(i), 0.5f, 2.0f);
    return img;
}

TEST(AtomicWrite, MissingDirectoryThrowsAndLeavesNothing) {
    TempDir dir;
    const std::string target = dir.file("no/such/dir/out.exr");
    try {
        write_image(target, small_image());
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("cannot write '" + target + "': ", 0), 0u) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("no")));
    EXPECT_EQ(entries(dir.path()), 0);
}

TEST(AtomicWrite, ReplacesExistingFile) {
    TempDir dir;
    const std::string target = dir.file("out.pfm");
    put(target, "old contents");
    write_image(target, small_image());
    EXPECT_EQ(read_image(target).at(2, 1), Rgb(5.0f, 0.5f, 2.0f));
    EXPECT_EQ(entries(dir.path()), 1);  // no temporary left behind
}

TEST(AtomicWrite, WriterFailingHalfwayKeepsOldFile) {
    TempDir dir;
    const std::string target = dir.file("out.png");
    put(target, "old contents");
    std::string temp_seen;
    try {
        atomic_write(target, [&](const std::string& temp) {
            temp_seen = temp;
            put(temp, "half a new fi");
            throw std::runtime_error("disk on fire");
        });
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "cannot write '" + target + "': disk on fire");
    }
    // The temporary was in the target's directory, and is gone; the old file is intact.
    EXPECT_EQ(std::filesystem::path(temp_seen).parent_path(), std::filesystem::path(dir.path()));
    EXPECT_FALSE(std::filesystem::exists(temp_seen));
    EXPECT_EQ(slurp(target), "old contents");
    EXPECT_EQ(entries(dir.path()), 1);
}

TEST(AtomicWrite, RenameFailureRemovesTemporary) {
    TempDir dir;
    // The target is a non-empty directory: everything succeeds until the rename, which must fail.
    const std::string target = dir.file("out.exr");
    std::filesystem::create_directory(target);
    put(target + "/keep", "x");
    EXPECT_THROW(write_image(target, small_image()), InputError);
    EXPECT_TRUE(std::filesystem::is_directory(target));
    EXPECT_EQ(slurp(target + "/keep"), "x");
    EXPECT_EQ(entries(dir.path()), 1);
}

TEST(AtomicWrite, WriterSeesAFreshEmptyFileAndResultIsComplete) {
    TempDir dir;
    const std::string target = dir.file("plain.txt");
    put(target, "previous");
    atomic_write(target, [&](const std::string& temp) {
        EXPECT_NE(temp, target);
        EXPECT_EQ(slurp(temp), "");
        put(temp, "new");
        EXPECT_EQ(slurp(target), "previous");  // not visible until the rename
    });
    EXPECT_EQ(slurp(target), "new");
    EXPECT_EQ(entries(dir.path()), 1);
}

}  // namespace
}  // namespace phos::io
