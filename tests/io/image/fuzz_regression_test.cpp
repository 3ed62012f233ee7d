// Inputs found by fuzzing the image readers (fuzz/image_fuzzer.cpp, scripts/fuzz.sh), kept as
// regression tests: each must be rejected with InputError, not corrupt memory; valid files of the
// same kind must still read.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/image/image_io.h"
#include "io/image/temp_dir.h"

namespace phos::io {
namespace {

using test::TempDir;

std::string from_hex(const std::string& hex) {
    std::string bytes;
    for (size_t i = 0; i + 1 < hex.size(); i += 2)
        bytes.push_back(char(std::stoi(hex.substr(i, 2), nullptr, 16)));
    return bytes;
}

std::string write(const TempDir& dir, const std::string& name, const std::string& bytes) {
    const std::string path = dir.file(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// Reading `path` must fail with InputError naming `reason`; `accepted` is the failure message
// when it is read instead.
void expect_refused(const std::string& path, const std::string& reason, const std::string& accepted) {
    try {
        read_image(path);
        ADD_FAILURE() << accepted;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
}

// An 8x8 grey baseline JPEG whose DC table has the given 16 code counts (as hex) and one symbol,
// and whose AC table has one code (as in fuzz/make_seeds.py).
std::string tiny_jpeg(const std::string& dc_counts) {
    std::string q = "ffdb004300";
    for (int i = 0; i < 64; ++i) q += "01";
    return from_hex("ffd8" + q + "ffc0000b080008000801011100" + "ffc40014" + "00" + dc_counts + "00" +
                    "ffc40014" + "10" + "01000000000000000000000000000000" + "00" + "ffda000801010000" +
                    "3f00" + "3f" + "ffd9");
}

// stb_image 2.27 builds a Huffman table from 16 code counts without checking that they add up to
// at most 256: counts of 0xFF overran the decoder's 257-byte size list (the fuzzer's input below,
// found as a UBSan out-of-bounds index; ASan sees the heap overflow of the symbol copy).
TEST(ImageFuzz, JpegHuffmanTableWithTooManyCodesIsRejected) {
    TempDir dir;
    const std::string found = from_hex(
        "ffd8ffdb00430001010101010101010101010101010101010101010101010101010101010101010101010101010101"
        "010101010101010101010101010101010101010101ffc0000b080008000801011100ffc40014000100000000000000"
        "0000ffffff010008000000000008000000000000000000000002000000000000000000000000003f003fffd9");
    // stb also takes a file starting with 0xFF fill bytes before the SOI marker for a JPEG (the
    // fuzzer's second input).
    for (const std::string& bytes :
         {found, tiny_jpeg("ffffffffffffffffffffffffffffffff"), "\xff\xff\xff" + found}) {
        expect_refused(write(dir, "bad.jpg", bytes), "Huffman table",
                       "accepted a JPEG with an impossible Huffman table");
    }
    // The same file with a proper table (one code) reads: an 8x8 mid-grey image.
    const Image ok = read_image(write(dir, "ok.jpg", tiny_jpeg("01000000000000000000000000000000")), false);
    ASSERT_EQ(ok.width, 8);
    ASSERT_EQ(ok.height, 8);
    EXPECT_NEAR(ok.at(3, 3).r, 128.0f / 255.0f, 1e-6f);
}

// A 22-byte run-length TGA claiming 65535 x 2817 pixels: stb_image allocates the whole image and
// then loops over every pixel although the file has ended (the fuzzer's timeout). Headers claiming
// implausibly many pixels for the file's size are refused before decoding.
TEST(ImageFuzz, HugeHeaderOnATinyFileIsRejected) {
    TempDir dir;
    const std::string tga = from_hex("00000a00000000000000ffffffff010b1860830a141e");
    expect_refused(write(dir, "huge.tga", tga), "implausibly many",
                   "accepted a 22-byte TGA of 65535 x 2817 pixels");
    // A real TGA of the same kind (one run of 4 pixels) still reads.
    const Image ok =
        read_image(write(dir, "ok.tga", from_hex("00000a0000000000000000000400010018208300ff00")), false);
    ASSERT_EQ(ok.width, 4);
    ASSERT_EQ(ok.height, 1);
    EXPECT_EQ(ok.at(3, 0), Rgb(0.0f, 1.0f, 0.0f));
}

// phos's own BMP truncation check multiplies the row size by the height, which must not overflow
// 64-bit signed arithmetic: 1,819,434,868 pixels wide (the bytes "t_rl" of a mangled HDR header) at
// 24 bits times 1,735,548,773 rows would (undefined behaviour, reported by UBSan). Such a header is
// refused as truncated.
TEST(ImageFuzz, BmpHeaderWhoseSizeOverflowsIsTruncated) {
    TempDir dir;
    const std::string found = from_hex(
        "424d46000000464f524d41543d33322d6269745f726c655f7267010018000000000010000000130b0000130b00000000"
        "00424d460000000000000036000000280000000a00233f524742450a000002000000010018000000000010000000130b"
        "0000130b00000000000000000000ffff000000ff0000ffffff0000");
    expect_refused(write(dir, "huge.bmp", found), "truncated BMP",
                   "accepted a 123-byte BMP whose header asks for more than 2^63 bytes");
}

// A 31-byte BMP whose 40-byte header is cut off after the height: 7178 x 63236 pixels (top-down)
// of 8 bits. stb reads the missing header bytes as zeros (uncompressed) and would decode 454 M
// pixels of nothing (the fuzzer's 12 s timeout), so the size check must not skip files shorter
// than the header it reads. A BMP must hold its whole header; the 12-byte core header's 16-bit
// sizes are checked against the file as well.
TEST(ImageFuzz, BmpWithATruncatedHeaderIsRejected) {
    TempDir dir;
    const std::string cut = from_hex(
        "424d"
        "bafa0000"
        "00000000"
        "34000000"
        "28000000"
        "0a1c0000"
        "fc08ffff"
        "0100"
        "0800");
    expect_refused(write(dir, "cut.bmp", cut), "truncated BMP header",
                   "accepted a 30-byte BMP whose header stops after its height");
    // The core header (12 bytes): 65535 x 65535 pixels of 24 bits in 32 bytes.
    const std::string core = from_hex(
        "424d20000000000000001a0000000c000000ffffffff01001800"
        "000000000000");
    expect_refused(write(dir, "core.bmp", core), "truncated BMP (",
                   "accepted a 32-byte core-header BMP claiming 65535 x 65535 pixels");
    // A valid core-header BMP still reads: 2 x 1 pixels, 24 bits, one padded row.
    const std::string valid = from_hex(
        "424d2200000000000000"
        "1a000000"
        "0c000000"
        "0200"
        "0100"
        "0100"
        "1800"
        "0000ff"
        "00ff00"
        "0000");
    const Image image = read_image(write(dir, "valid.bmp", valid));
    EXPECT_EQ(image.width, 2);
    EXPECT_EQ(image.height, 1);
}

// A 148-byte EXR whose data window is 33,537,537 pixels wide: opening it, OpenEXR allocates line
// buffers for 32 lines of that width (2.2 GB, the image fuzzer's out-of-memory finding). The
// header's data window (and the buffers it implies) is checked from the file's bytes before
// OpenEXR opens it.
TEST(ImageFuzz, ExrWithAHugeDataWindowIsRejectedBeforeOpenExrAllocates) {
    TempDir dir;
    const std::string found = from_hex(
        "762f3101020000006368616e6e656c730063686c697374001300000059000200000000000000010000000100000000"
        "636f6d70f273696f6e00636f6d7072657373696f6e0001000000006461746157696e646f7700626f7832690010000000"
        "004200000000000000000002f900000000006f77576964746800666c6fff1400040000000000803f001d00003f000000"
        "3f0000003f");
    expect_refused(write(dir, "wide.exr", found), "unsupported EXR data window size",
                   "accepted a 148-byte EXR 33.5 M pixels wide");
}

// Radiance HDR: stb ends the header at a line whose first byte is 0 (it reads lines as C strings).
// A walk of the run-length scanlines that waits for a truly empty line misses the pixels and lets
// through a scanline whose last run is cut off, on which stb loops for ever (the fuzzer's
// timeouts), so phos's walk ends the header where stb does.
TEST(ImageFuzz, HdrHeaderEndedByANulLineIsWalkedAsStbReadsIt) {
    TempDir dir;
    const std::string found = from_hex(
        "233f52414449414e43450a6269745f726c650a464f524d41543d33322d6269745f726c655f726762650a000a2d5920"
        "31202b5820380a020200088801010100000182");
    expect_refused(write(dir, "nul.hdr", found), "corrupt HDR",
                   "accepted a cut-off run-length HDR whose header ends with a NUL line");
}

// A BMP whose compression field holds no known code (0xBB000000): stb reads it as uncompressed
// pixels, 3 wide and 14,417,922 rows (a negative height: top-down), skipping each row's padding
// with a seek (the fuzzer's timeout). Unknown codes are refused, not left to stb.
TEST(ImageFuzz, BmpWithAnUnknownCompressionCodeIsRejected) {
    TempDir dir;
    const std::string found = from_hex(
        "424d00460000000000002e0000002800000003000000feff23ff01000800000000bb000800000000000000"
        "000000000000000000000000000000fffffffffffffffffffffffdffffffffffffffffffffffffff000020");
    expect_refused(write(dir, "rows.bmp", found), "unsupported BMP compression",
                   "accepted an 86-byte BMP with compression code 0xBB000000");
}

// A 98-byte run-length TGA claiming 512 x 6144 pixels: stb fills what the file lacks, so it
// would decode 3.1 M pixels (the fuzzer's timeout, under load). Run-length packets encode
// at most 128 pixels in 2 bytes, so TGA headers are held to 64 pixels per byte; a valid file
// at that limit (one grey value, every packet a full run) still reads.
TEST(ImageFuzz, RunLengthTgaClaimingMorePixelsThanPacketsCanHoldIsRejected) {
    TempDir dir;
    const std::string found = from_hex(
        "00000a00000000000000000000020018186088888888888888888888888888888888888888888888888888888888888888"
        "88888888888888888888888888888888888888888888888888888888888888888888888888888888888888888802020000");
    // stb recognises TGA by content: the bound holds whatever the name (the fuzzer's third input
    // was a TGA named .jpg).
    for (const char* name : {"rle.tga", "rle.jpg"}) {
        expect_refused(write(dir, name, found), "implausibly many",
                       std::string(name) + ": accepted a 98-byte TGA claiming 512 x 6144 pixels");
    }
    // 256 x 256 grey pixels of value 200 in 512 full run packets (0xFF = run of 128, then the value).
    std::string tga(18, '\0');
    tga[2] = 11;                                         // run-length grey
    tga[12] = 0, tga[13] = 1, tga[14] = 0, tga[15] = 1;  // 256 x 256
    tga[16] = 8;
    for (int k = 0; k < 512; ++k) tga += std::string{char(0xFF), char(200)};
    const Image img = read_image(write(dir, "dense.tga", tga), false);
    ASSERT_EQ(img.width, 256);
    ASSERT_EQ(img.height, 256);
    EXPECT_NEAR(img.pixels[12345].g, 200.0f / 255.0f, 1e-6f);
}

// stb_image loops forever on a run-length encoded Radiance HDR scanline that ends early (at the end
// of the file it reads a "dump" count of 0 again and again): the fuzzer's input below, 8 pixels
// wide, has a run for one component and then ends. Such files are refused before decoding.
TEST(ImageFuzz, TruncatedRunLengthHdrIsRejected) {
    TempDir dir;
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n";
    const std::string found = header + from_hex("020200088801010101010101");
    expect_refused(write(dir, "cut.hdr", found), "corrupt HDR", "accepted a truncated run-length HDR");
    // The whole scanline (a run of 8 for each component) reads.
    const Image ok = read_image(write(dir, "ok.hdr", header + from_hex("020200088864883288198880")), false);
    ASSERT_EQ(ok.width, 8);
    ASSERT_EQ(ok.height, 1);
    EXPECT_GT(ok.at(7, 0).r, ok.at(7, 0).g);
}

// OpenEXR allocates and clears an attribute's claimed size before it finds the file too short: in
// the fuzzer's 369-byte file below, a "string" attribute claims 846 MB (its size field is the
// bytes "box2"), which takes 0.6 s and times out under the address sanitizer. Attribute sizes are
// checked against the file first. Valid files, single- and multi-part, still read.
TEST(ImageFuzz, ExrAttributeClaimingMoreThanTheFileIsRejected) {
    TempDir dir;
    const std::string found = from_hex(
        "762f3101020000006368616e6e656c730063686c69737400370000005200010000000000000001000000010000004700"
        "0100000000000000010000000100000042000100000000000000010000000100000000636f6d7072657373696f6e0063"
        "6f6d7072657373696f6e00010000007479706500737472696e6700626f78326900100000000000000000000000010000"
        "0001000000646973706c617957696e646f7700626f7832690010000000000000000000000001000000010000006c696e"
        "654f72646572006c696e654f72646572000100000000706978656c417370656374526174696f00666c6f617400040000"
        "000000803f73637265656e57696e646f7743656e746572007632660008000000000000000000000073637265656e5769"
        "6e646f77576964746800666c6f617400040000000000803f0049010000000000005d01000000000000000000000c0000"
        "00003800380038003800380038010000000c000000003800380038003800380038");
    expect_refused(write(dir, "huge.exr", found), "claims 846753634 bytes",
                   "accepted an EXR with a huge attribute");

    Image image(3, 2);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = Rgb(float(i), 0.5f, 2.0f);
    const std::string single = dir.file("single.exr");
    write_image(single, image);
    const Image back = read_image(single);
    ASSERT_EQ(back.width, 3);
    EXPECT_EQ(back.pixels[5].r, 5.0f);

    // Two parts: the check walks both headers (each ended by a null byte, the list by an empty one).
    const std::string multi = dir.file("multi.exr");
    {
        std::vector<Imf::Header> headers(2, Imf::Header(3, 2));
        for (int p = 0; p < 2; ++p) {
            headers[size_t(p)].setName(p == 0 ? "beauty" : "other");
            headers[size_t(p)].setType(Imf::SCANLINEIMAGE);
            headers[size_t(p)].channels().insert("R", Imf::Channel(Imf::FLOAT));
        }
        Imf::MultiPartOutputFile out(multi.c_str(), headers.data(), 2);
        for (int p = 0; p < 2; ++p) {
            Imf::OutputPart part(out, p);
            std::vector<float> r(6, float(p + 1));
            Imf::FrameBuffer fb;
            fb.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(r.data()), sizeof(float),
                                      3 * sizeof(float)));
            part.setFrameBuffer(fb);
            part.writePixels(2);
        }
    }
    const Image first = read_image(multi);
    ASSERT_EQ(first.width, 3);
    EXPECT_EQ(first.pixels[0].r, 1.0f);  // the first part
}

// stb_image multiplies a JPEG block's DC prediction, which the file steers block after block, by a
// 16-bit quantiser in int: the fuzzer's file below overflows it (-33215 * 65535), undefined
// behaviour that UBSan stops on. stb_image.cpp is compiled with -fwrapv, so the arithmetic
// wraps by definition: the file decodes to some pixels or is refused, either way without undefined
// behaviour (this test fails under `scripts/test.sh --sanitize` without the flag).
TEST(ImageFuzz, JpegWithAnOverflowingDcPredictionIsDefined) {
    TempDir dir;
    const std::string found = from_hex(
        "ffd8ffdb004301010101010101010101010101010101010101010101ffc0000b080408000801011100ffc40014000100"
        "000200000000000000000000000009ffc400141001000000000000000000000000000001010101010101010101494441"
        "5401010101010101010101010101010101010101010101010101ffc0000b080408000801011100ffc400140001000000"
        "00000000000000000000000009ffc40014100100000000000000000000000000000000ffda0008010100000000ffda00"
        "08010100003f000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
        "000000000000003f01010101d8fefefefefefefa01010101010101fe0001010100003f003fffd9");
    try {
        const Image image = read_image(write(dir, "dc.jpeg", found), true);
        EXPECT_EQ(image.pixels.size(), size_t(image.width) * size_t(image.height));
    } catch (const InputError&) {
    }
}

// stb_image decodes a scan with whatever Huffman table the scan names, defined or not: in the
// fuzzer's file below the scan's AC table 1 is never defined, and the table's uninitialised
// limits give a symbol index of -56837 (an out-of-bounds read; UBSan's finding). Such files are
// refused; a progressive file whose scans use only the tables they need (DC-first scans no AC
// table, DC refinements none, AC scans no DC table, an AC table defined after the DC scan) is not.
TEST(ImageFuzz, JpegScanWithAnUndefinedHuffmanTableIsRejected) {
    TempDir dir;
    const std::string found = from_hex(
        "ffd8ffdb0043000101010101010101015e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e5e"
        "5e5e5e5e405e5f5e5e5e5e5e5e5e5e5e5e5e315e5e6c696e654f72646572006c01fd01ffc0000b080008000801011100"
        "ffc40014000100000000000000000000000000000000ffc40014100100000000000000000000000000000068ffda0008"
        "010101003f003f636875504c54456e6b436f9594a72ffe7f0000000014100100000000000000000000000000000000ff"
        "da000801010000000000000000000f460700406000000000000000000000000000000000000000000000000e00000000"
        "6e74696e7400ffd9");
    expect_refused(write(dir, "undefined.jpg", found), "no DHT segment defines",
                   "accepted a scan with an undefined Huffman table");

    std::string q = "ffdb004300";
    for (int i = 0; i < 64; ++i) q += "01";
    const std::string dc_table =
        "ffc40014"
        "00"
        "01000000000000000000000000000000"
        "00";
    const std::string ac_table =
        "ffc40014"
        "10"
        "01000000000000000000000000000000"
        "00";
    const std::string progressive = from_hex("ffd8" + q + "ffc2000b080008000801011100" + dc_table +
                                             "ffda0008010101000000" + "00" +  // DC first: td 0 (ta 1 unused)
                                             "ffda0008010132000010" + "00" +  // DC refinement: no table
                                             ac_table + "ffda0008010120013f00" + "00" + "ffd9");
    try {
        read_image(write(dir, "progressive.jpg", progressive));
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find("no DHT segment defines"), std::string::npos) << e.what();
    }
}

// stb_image's file reader keeps only its first 128 bytes for the rewinds between its format tests:
// the fuzzer's 245-byte JPEG below starts with 137 fill bytes, so after the JPEG test stb would
// decode bytes 128.. followed by stale buffer bytes, whose DHT holds code counts the file does not,
// and build a Huffman table past its 257-entry size list (UBSan, stb_image.h:1990), bytes phos's
// checks never saw. stb decodes the bytes phos checked, from memory: the file is refused
// (its only Huffman table is cut off), and a valid JPEG behind 137 fill bytes reads exactly as
// without them.
TEST(ImageFuzz, JpegBehindFillBytesIsDecodedFromTheBytesThatWereChecked) {
    TempDir dir;
    const std::string fill(137, char(0xff));
    const std::string found =
        fill +
        from_hex(
            "d8ffdb004300013e00420000000000000000000000000000000000000000000000000000000000015e000000815e5e5e"
            "5e5e5e5e4073637265656e57696e646f7743656e7465720076326600d9fd01ffc2000b080008000801011100ffc40014"
            "0001000000000000000000");
    EXPECT_THROW(read_image(write(dir, "fill.jpg", found)), InputError);

    const std::string valid = tiny_jpeg("01000000000000000000000000000000");
    const Image plain = read_image(write(dir, "plain.jpg", valid));
    const Image filled = read_image(write(dir, "filled.jpg", fill + valid.substr(1)));  // FF.. FF D8
    ASSERT_EQ(plain.width, 8);
    ASSERT_EQ(filled.width, plain.width);
    ASSERT_EQ(filled.height, plain.height);
    for (size_t i = 0; i < plain.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(filled.pixels[i][c], plain.pixels[i][c]) << i;
}

// An empty file is refused by every stb-decoded format (the fuzzer's one-byte input: for an empty
// BMP the BMP check must not copy from a null pointer).
TEST(ImageFuzz, EmptyFilesAreRefused) {
    TempDir dir;
    for (const char* name : {"e.png", "e.jpg", "e.jpeg", "e.tga", "e.bmp", "e.hdr"})
        EXPECT_THROW(read_image(write(dir, name, "")), InputError) << name;
}

// stb_image grows its buffer to a PNG IDAT chunk's claimed length before reading it: the fuzzer's
// 92-byte file below claims a chunk of 1.9 GB, which stb allocated (the fuzzer's out-of-memory
// finding). Chunks claiming more than the file holds are refused first; a valid PNG (written by
// phos, several chunks) still reads.
TEST(ImageFuzz, PngChunkClaimingMoreThanTheFileIsRejected) {
    TempDir dir;
    const std::string found = from_hex(
        "89504e470d0a1a0a0000000d49484452000000470000000801000000019b73b3b00000000d49444154789c5374313372"
        "756e74696d655f6572726f72000d49444154e8e810171717e8e8e8e8e8e8e8e8e8e8e80049454e44ae426082");
    expect_refused(write(dir, "chunk.png", found), "claims 1869742093 bytes",
                   "accepted a PNG chunk longer than the file");
    Image image(5, 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = Rgb(0.1f * float(i % 10), 0.5f, 0.25f);
    const std::string ok = dir.file("ok.png");
    write_image(ok, image);
    const Image back = read_image(ok, false);
    ASSERT_EQ(back.width, 5);
    ASSERT_EQ(back.height, 3);
}

}  // namespace
}  // namespace phos::io
