// Tests of the compressed-input reader (io/gzip): gzip streams decompress to what was compressed
// (text, binary, empty, several members one after the other, trailing zero padding), files without
// the gzip magic are read as they are, and damaged streams (truncated, corrupted, followed by other
// bytes, larger than the limit) are errors at the file that print none of its bytes.
#include "io/gzip/gzip_file.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "support/gzip_writer.h"
#include "test_util.h"

namespace phos::io {
namespace {

using phos::testing::gzip_bytes;

std::string random_bytes(size_t n, uint64_t seed) {
    Sampler rng(seed);
    std::string s(n, '\0');
    for (char& c : s) c = char(rng.next_index(256));
    return s;
}

// The message of the ParseError `f` throws (empty if it throws none).
template <class F>
std::string parse_error_of(F&& f) {
    try {
        f();
    } catch (const ParseError& e) {
        EXPECT_EQ(e.line, 0);
        return e.what();
    }
    ADD_FAILURE() << "no ParseError";
    return "";
}

bool printable(const std::string& s) {
    for (const char c : s)
        if ((static_cast<unsigned char>(c) < 32 && c != '\n') || static_cast<unsigned char>(c) > 126)
            return false;
    return true;
}

TEST(Gzip, StreamsDecompressToWhatWasCompressed) {
    const std::string text = "WorldBegin\nShape \"sphere\"\n";
    EXPECT_EQ(gunzip(gzip_bytes(text), "a.gz"), text);
    const std::string binary = random_bytes(300000, 1);  // several output buffers, incompressible
    EXPECT_EQ(gunzip(gzip_bytes(binary), "b.gz"), binary);
    EXPECT_EQ(gunzip(gzip_bytes(""), "c.gz"), "");
    std::string big(5 << 20, 'x');  // compresses ~1000:1
    EXPECT_EQ(gunzip(gzip_bytes(big), "d.gz"), big);
    // Members one after the other (`cat a.gz b.gz`), and zero padding after the last.
    EXPECT_EQ(gunzip(gzip_bytes(text) + gzip_bytes(binary) + std::string(7, '\0'), "e.gz"), text + binary);
}

TEST(Gzip, FilesAreReadDecompressedOnlyWhenTheyStartWithTheMagic) {
    phos::testing::TempDir dir;
    const std::string text = "ply\nformat ascii 1.0\n";
    std::string out;
    ASSERT_TRUE(read_maybe_gzip(dir.write("plain.ply.gz", text), out));  // the name does not decide
    EXPECT_EQ(out, text);
    ASSERT_TRUE(read_maybe_gzip(dir.write("packed.ply", gzip_bytes(text)), out));
    EXPECT_EQ(out, text);
    EXPECT_FALSE(read_maybe_gzip(dir.file("missing.ply"), out));
    for (const char* name : {"plain.ply.gz", "packed.ply"}) {
        const auto in = open_maybe_gzip(dir.file(name));
        ASSERT_TRUE(in);
        EXPECT_EQ(std::string(std::istreambuf_iterator<char>(*in), {}), text) << name;
    }
    EXPECT_FALSE(open_maybe_gzip(dir.file("missing.ply")));
    EXPECT_TRUE(is_gzip(gzip_bytes("")));
    EXPECT_FALSE(is_gzip("\x1f"));
}

TEST(Gzip, DamagedStreamsAreErrorsThatPrintNoneOfTheirBytes) {
    const std::string data = random_bytes(20000, 2);
    const std::string gz = gzip_bytes(data);
    // Truncated anywhere: in the header, the compressed blocks or the trailer.
    for (const size_t keep : {size_t(5), size_t(12), gz.size() / 2, gz.size() - 4, gz.size() - 1}) {
        const std::string msg = parse_error_of([&] { gunzip(gz.substr(0, keep), "t.gz"); });
        EXPECT_NE(msg.find("t.gz: corrupt gzip stream"), std::string::npos) << msg;
        EXPECT_TRUE(printable(msg)) << msg;
    }
    // A flipped byte in the compressed data (or the CRC-32 of the trailer) is found.
    for (const size_t at : {gz.size() / 3, gz.size() - 6}) {
        std::string bad = gz;
        bad[at] = char(bad[at] ^ 0x55);
        const std::string msg = parse_error_of([&] { gunzip(bad, "f.gz"); });
        EXPECT_NE(msg.find("corrupt gzip stream"), std::string::npos) << msg;
        EXPECT_TRUE(printable(msg)) << msg;
    }
    // Other bytes after the stream, and a stream over the size limit.
    const std::string after = parse_error_of([&] { gunzip(gz + "\xff\xfe binary", "g.gz"); });
    EXPECT_NE(after.find("unexpected bytes after the end"), std::string::npos) << after;
    EXPECT_TRUE(printable(after)) << after;
    const std::string limit =
        parse_error_of([&] { gunzip(gzip_bytes(std::string(100000, 'a')), "h.gz", 99999); });
    EXPECT_NE(limit.find("more than 99999 bytes"), std::string::npos) << limit;
}

}  // namespace
}  // namespace phos::io
