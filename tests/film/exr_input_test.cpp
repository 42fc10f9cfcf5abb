// EXR inputs of glint compare, convert and merge that lie or break: a header declaring a window
// its file cannot hold, a truncated file, inverted and negative windows, channels that are not
// RGB, NaN and infinite pixels. Each gives a result or a clean error naming the file (exit 2:
// the file the user named is unusable, as with a scene error), never a crash or an allocation
// the file's data does not back. The hostile headers are tests/fuzz/regressions-exr/ (written by
// tests/fuzz/make-hostile-exrs.py, 0.3–10 kB each).
#include <gtest/gtest.h>
#include <malloc.h>
#include <sys/resource.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "film/exr_input.h"
#include "film/exr_output.h"
#include "film/image_limits.h"
#include "film/merge.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::runGlint;

const fs::path kHostile = fs::path(GLINT_SOURCE_DIR) / "tests/fuzz/regressions-exr";

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

// The message of the UsageError readImage throws for `path`, or "(read)".
std::string readError(const std::string& path, ExrParts parts = ExrParts::First) {
  try {
    readImage(path, parts);
    return "(read)";
  } catch (const UsageError& e) {
    return e.what();
  }
}

// An RGB(A) float EXR of w × h pixels of one value, through OpenImageIO.
void writeFlat(const std::string& path, int w, int h, const std::vector<std::string>& channels,
               float value) {
  OIIO::ImageSpec spec(w, h, int(channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = channels;
  std::vector<float> pixels(size_t(w) * size_t(h) * channels.size(), value);
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  ASSERT_TRUE(out->close());
}

long peakRssKb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

TEST(ExrInput, ADataWindowThatDoesNotFitIsRefusedBeforeAllocating) {
  // 20000 × 20000 RGBA float in a 10 kB header: 6.4 GB. With a 1 GB budget it is refused by
  // its declared size, naming the file.
  const std::string huge = (kHostile / "huge-data-window.exr").string();
  setImageMemoryBudget(uint64_t{1} << 30);
  const std::string message = readError(huge);
  setImageMemoryBudget(0);
  EXPECT_NE(message.find(huge + ": its data window 20000x20000 needs 6.4 GB to read, more than "
                                "the 1.1 GB of memory available"),
            std::string::npos)
      << message;
}

TEST(ExrInput, PixelsAreAllocatedOnlyAsTheFileDeliversThem) {
  // Where the 6.4 GB would fit (this machine's memory), reading stops at the first band the file
  // does not hold: the error names the file, and the process never held more than the bands
  // read (16 MB each), far below the 6.4 GB the header claims. It once took 6.4 GB and minutes.
  const std::string huge = (kHostile / "huge-data-window.exr").string();
  setImageMemoryBudget(uint64_t{1} << 40);  // as if 1 TB were free: only the reading bounds it
  const std::string message = readError(huge);
  setImageMemoryBudget(0);
  EXPECT_NE(message.find("cannot read " + huge), std::string::npos) << message;
  EXPECT_LT(peakRssKb(), 1024 * 1024) << "peak RSS in kB; the header asks for 6.4 GB";
}

TEST(ExrInput, ATiledLayeredFileOfManyBandsReadsAsOpenImageIOReadsIt) {
  // 2048 x 1100 pixels of 5 float channels (45 MB: three 16 MB bands), tiled 64 x 64 with a
  // data window starting at (-7, 13) and an AOV layer: every value must land where OpenImageIO,
  // an independent reader, puts it, and the channels come layer by layer, R, G, B, A first.
  const int w = 2048, h = 1100;
  OIIO::ImageSpec spec(w, h, 5, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"A", "B", "G", "R", "depth.Z"};
  spec.alpha_channel = 0;
  spec.x = -7;
  spec.y = 13;
  spec.tile_width = spec.tile_height = 64;
  std::vector<float> pixels(size_t(w) * h * 5);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> value(-2.0f, 8.0f);
  for (float& v : pixels) v = value(rng);
  const std::string path = tmp("tiled-bands.exr");
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());

  const Image img = readImage(path);
  ASSERT_EQ(img.width, w);
  ASSERT_EQ(img.height, h);
  EXPECT_EQ(img.x, -7);
  EXPECT_EQ(img.y, 13);
  EXPECT_EQ(img.channelNames, (std::vector<std::string>{"R", "G", "B", "A", "depth.Z"}));
  auto in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in);
  // OpenImageIO's own order of the file's channels, to map each of Glint's onto it.
  const std::vector<std::string>& theirs = in->spec().channelnames;
  std::vector<float> expected(pixels.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 5, OIIO::TypeDesc::FLOAT, expected.data()));
  size_t mismatches = 0;
  for (int c = 0; c < 5; ++c) {
    const size_t k = size_t(std::find(theirs.begin(), theirs.end(), img.channelNames[size_t(c)]) -
                            theirs.begin());
    ASSERT_LT(k, 5u) << img.channelNames[size_t(c)];
    for (size_t p = 0; p < size_t(w) * h; ++p)
      mismatches += img.pixels[p * 5 + size_t(c)] != expected[p * 5 + k];
  }
  EXPECT_EQ(mismatches, 0u);
}

TEST(ExrInput, TilesLargerThan4096PixelsAreRefusedNamingTheFile) {
  // OpenEXR caches a whole row of tiles as it reads: a file that declares one tile of 20000
  // rows (a 10 kB file can) would allocate it at once. A 1 x 5000 image in one 1 x 5000 tile
  // is past the limit (kMaxTileEdge, 4096).
  OIIO::ImageSpec spec(1, 5000, 3, OIIO::TypeDesc::HALF);
  spec.tile_width = 1;
  spec.tile_height = 5000;
  const std::vector<uint16_t> zeros(size_t(5000) * 3, 0);
  const std::string path = tmp("tall-tile.exr");
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, spec) &&
              out->write_image(OIIO::TypeDesc::HALF, zeros.data()) && out->close());
  const std::string error = readError(path);
  EXPECT_EQ(error.rfind("cannot read " + path + ": ", 0), 0u) << error;
  EXPECT_NE(error.find("tile"), std::string::npos) << error;
}

TEST(ExrInput, BlocksLargerThan200MibAreRefusedNamingThePart) {
  // OpenEXR sizes its line buffers and decompressor by the block: 500000 RGBA floats in DWAB's
  // 256-line blocks are 1953 MiB in a 339-byte file (glint_fuzz_exr found a 2.16 GB allocation).
  const std::string lines = (kHostile / "line-block-of-2-GB.exr").string();
  EXPECT_NE(readError(lines).find("cannot read " + lines +
                                  ": part 0 is decoded in blocks of 1953 MiB (its width by the "
                                  "lines decoded together); blocks of at most 200 MiB are read"),
            std::string::npos)
      << readError(lines);
  // A tiled part's block is its row of tiles, which OpenEXR caches as floats: 245 tiles of
  // 4096 x 4096 across a 1000000-pixel row are 15680 MiB, though each tile is 64 MiB.
  const std::string tiles = (kHostile / "tiled-row-of-15-GB.exr").string();
  EXPECT_NE(readError(tiles).find(": part 0 is decoded in blocks of 15680 MiB"), std::string::npos)
      << readError(tiles);
}

// Bytes malloc has handed out and not taken back, touched or not (glibc's counts).
int64_t allocatedBytes() {
  const struct mallinfo2 info = mallinfo2();
  return int64_t(info.uordblks + info.hblkhd);
}

// What OpenEXR holds to decode part 0 of `path` once it has opened the part and decoded its
// first block (DWA allocates its scratch then), as openExr opens it.
int64_t decodingAllocation(const std::string& path) {
  const auto file = openExr(path);
  const int64_t before = allocatedBytes();
  Imf::InputPart part(*file, 0);
  const ExrWindow w = exrWindow(path, part.header());
  const std::vector<std::string> channels = channelsInReadingOrder(part.header().channels());
  std::vector<float> row(size_t(w.width) * channels.size());
  Imf::FrameBuffer frameBuffer;
  for (size_t c = 0; c < channels.size(); ++c)
    frameBuffer.insert(
        channels[c], Imf::Slice::Make(Imf::FLOAT, row.data() + c, Imath::V2i(w.x, w.y), w.width, 1,
                                      channels.size() * sizeof(float), size_t{0}));
  part.setFrameBuffer(frameBuffer);
  try {
    part.readPixels(w.y, w.y);
  } catch (const std::exception&) {
    // The all-zero chunk is not every method's valid data: what was set up for it counts.
  }
  return allocatedBytes() - before - int64_t(row.size() * sizeof(float));
}

TEST(ExrInput, DecodingBuffersStayWithinTheBudgetAtSixteenThreads) {
  if (test::kAddressSanitizer)
    GTEST_SKIP() << "AddressSanitizer's allocator does not keep mallinfo2's counts";
  {
    const int64_t before = allocatedBytes();
    std::vector<char> probe(64 << 20);
    if (allocatedBytes() - before < int64_t(probe.size()))
      GTEST_SKIP() << "this allocator does not keep glibc's mallinfo2 counts";
  }
  struct ExrThreads {
    const int before = Imf::globalThreadCount();
    ExrThreads() { setExrThreads(16); }
    ~ExrThreads() { setExrThreads(before); }
  } sixteen;
  // A 50000-pixel RGBA float row (blocks of up to 195 MiB, within the limit) under every
  // compression method, with one all-zero 88-byte chunk (a DWA chunk of zeros): at 16 threads
  // OpenEXR would set up two buffers a thread, each a block and its decompressor's scratch
  // (6.4 GB of DWAB blocks at opening alone). What it holds must stay within
  // kExrDecodingBudget.
  std::ifstream in(kHostile / "line-block-of-205-MB.exr", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string attribute("compression\0compression\0", 24);
  const size_t found = bytes.find(attribute);
  ASSERT_NE(found, std::string::npos);
  const size_t at = found + attribute.size() + 4;   // after the value's size
  const char chunk[8] = {0, 0, 0, 0, 88, 0, 0, 0};  // line 0, 88 bytes
  bytes += std::string(chunk, sizeof chunk) + std::string(88, '\0');
  for (int method = 0; method < Imf::NUM_COMPRESSION_METHODS; ++method) {
    bytes[at] = char(method);
    const std::string path = tmp("block-" + std::to_string(method) + ".exr");
    std::ofstream(path, std::ios::binary) << bytes;
    EXPECT_LE(decodingAllocation(path), int64_t(kExrDecodingBudget))
        << "compression method " << method;
  }
  // A tiled DWAA part whose row of 4096 x 4096 tiles is 192 MiB: the cache and DWA's scratch.
  EXPECT_LE(decodingAllocation((kHostile / "tiled-dwaa-row-of-192-MiB.exr").string()),
            int64_t(kExrDecodingBudget));
}

TEST(ExrInput, AHeaderAttributeLargerThanTheFileIsRefused) {
  // A 400-byte file whose "comments" string declares 900 MB: OpenEXR allocated the declared
  // size before reading (glint_fuzz_exr: 1.8 GB from 1.7 kB). Glint walks the header first.
  const std::string lie = (kHostile / "string-attribute-declaring-900-MB.exr").string();
  EXPECT_NE(readError(lie).find("cannot read " + lie +
                                ": its header attribute \"comments\" declares 900000000 bytes, "
                                "but the file has "),
            std::string::npos)
      << readError(lie);
  // Only OpenEXR reads: another format OpenImageIO knows (a PNG) is not an EXR here.
  const std::string png = tmp("image.png");
  OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::UINT8);
  std::vector<unsigned char> pixels(12, 128);
  auto out = OIIO::ImageOutput::create(png);
  ASSERT_TRUE(out && out->open(png, spec) &&
              out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) && out->close());
  EXPECT_EQ(readError(png), "cannot read " + png + ": not an OpenEXR file");
}

TEST(ExrInput, CommandsNameTheFileOfABadHeader) {
  // compare, convert and merge each refuse a lying or broken header with exit 2, naming it.
  for (const char* name : {"huge-data-window.exr", "inverted-data-window.exr"}) {
    const std::string bad = (kHostile / name).string();
    for (const std::string& args :
         {"compare " + bad + " " + bad, "convert " + bad + " " + tmp("bad.png"),
          "merge " + tmp("bad-merged.exr") + " " + bad}) {
      const auto r = runGlint(args);
      EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
      EXPECT_NE(r.output.find(bad), std::string::npos) << args << "\n" << r.output;
    }
  }
}

TEST(ExrInput, ATruncatedFileIsAnErrorNamingIt) {
  const std::string scene =
      test::writeTemp("exr-input.json", R"({"render": {"width": 32, "height": 16, "spp": 1},
        "camera": {"eye": [0,0,4], "look_at": [0,0,0]}, "materials": {"m": {"type": "phong"}},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  const std::string whole = tmp("whole.exr"), cut = tmp("truncated.exr");
  ASSERT_EQ(runGlint("render " + scene + " --quiet --compression none -o " + whole).exitCode, 0);
  fs::copy_file(whole, cut, fs::copy_options::overwrite_existing);
  fs::resize_file(cut, fs::file_size(whole) / 2);  // half of the pixel rows are gone
  for (const std::string& args :
       {"compare " + cut + " " + whole, "convert " + cut + " " + tmp("cut.png")}) {
    const auto r = runGlint(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("cannot read " + cut), std::string::npos) << r.output;
  }
}

TEST(ExrInput, NegativeAndOutsideDataWindowsAreReadOrRefusedByMerge) {
  // A 2 × 1 data window at (-7, -5), outside its 2 × 2 display window: a valid EXR. compare and
  // convert read its pixels (0.5 everywhere, so against itself rmse = 0); merge, which places
  // crops in the frame, refuses it by name.
  const std::string outside = (kHostile / "data-window-outside-display-window.exr").string();
  const Image img = readImage(outside);
  EXPECT_EQ(img.x, -7);
  EXPECT_EQ(img.y, -5);
  EXPECT_EQ(img.width, 2);
  EXPECT_EQ(img.pixels, std::vector<float>(6, 0.5f));
  const auto c = runGlint("compare " + outside + " " + outside);
  EXPECT_EQ(c.exitCode, 0) << c.output;
  EXPECT_NE(c.output.find("rmse      0\n"), std::string::npos) << c.output;
  const auto m = runGlint("merge " + tmp("outside-merged.exr") + " " + outside);
  EXPECT_EQ(m.exitCode, 2) << m.output;
  EXPECT_NE(m.output.find(outside + ": data window lies outside the frame"), std::string::npos)
      << m.output;
}

TEST(ExrInput, AHugeFrameAroundOneCropIsReportedWithoutAllocatingIt) {
  // One 1 × 1 crop of a 60000 × 60000 frame: merge once allocated 57 GB for the frame before
  // finding it incomplete. The holes are found on the crops' rectangles: two regions, greedily
  // (film/merge.h): from (1, 0) right to the edge and down to the bottom, then column 0 below
  // the crop.
  const std::string crop = (kHostile / "huge-display-window-merge.exr").string();
  const auto r = runGlint("merge " + tmp("huge-merged.exr") + " " + crop);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("the crops leave 2 region(s) of the 60000x60000 frame of " + crop +
                          " unrendered; render them with:\n  --crop 1 60000 0 60000\n  --crop 0 1 "
                          "1 60000"),
            std::string::npos)
      << r.output;
}

TEST(ExrInput, MergeRefusesACropHoldingNaNNamingItAndThePixel) {
  // A whole 2 x 1 frame, its second pixel NaN in B, G and R: merge copied it into the merged
  // frame, exit 0. Glint writes no NaN or Inf, so the crop was altered: exit 2, naming the
  // file, the first channel in the file's order (B) and the pixel, and no frame written.
  const std::string crop = (kHostile / "nan-pixel-copied-into-the-merged-frame.exr").string();
  const std::string out = tmp("nan-merged.exr");
  const auto r = runGlint("merge " + out + " " + crop);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(crop + ": channel B is NaN at pixel (1, 0)"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ExrInput, ConvergeRefusesAReferenceHoldingNaN) {
  // Every error against it was +inf or NaN: a table of "-nan" and a plot axis at 10^(int)NaN,
  // exit 0. Refused, naming the file, the channel and the pixel.
  const std::string reference = (kHostile / "nan-pixel-copied-into-the-merged-frame.exr").string();
  const std::string scene = test::writeTemp("converge-nan.json", R"({"render": {"width": 2,
    "height": 1}, "camera": {"eye": [0,0,4], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  const auto r = runGlint("converge " + scene + " --spp 1,2 --reference " + reference);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(reference + ": channel R is NaN at pixel (1, 0)"), std::string::npos)
      << r.output;
}

TEST(ExrInput, MissingRegionsOfRectanglesMatchThoseOfPixels) {
  // The rectangle search must give exactly the pixel search's regions: 200 random sets of
  // non-overlapping crops of a 13 × 11 frame, each compared with the mask version.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<PixelWindow> crops;
    std::vector<bool> mask(13 * 11, false);
    for (int k = 0; k < 6; ++k) {
      const int x0 = int(rng() % 13), y0 = int(rng() % 11);
      const PixelWindow c{x0, x0 + 1 + int(rng() % size_t(13 - x0)), y0,
                          y0 + 1 + int(rng() % size_t(11 - y0))};
      bool overlaps = false;
      for (int y = c.y0; y < c.y1; ++y)
        for (int x = c.x0; x < c.x1; ++x) overlaps = overlaps || mask[size_t(y) * 13 + size_t(x)];
      if (overlaps) continue;
      for (int y = c.y0; y < c.y1; ++y)
        for (int x = c.x0; x < c.x1; ++x) mask[size_t(y) * 13 + size_t(x)] = true;
      crops.push_back(c);
    }
    const auto byPixels = missingRegions(mask, 13, 11);
    const auto byRects = missingRegions(crops, 13, 11);
    ASSERT_EQ(byRects.size(), byPixels.size()) << "trial " << trial;
    for (size_t i = 0; i < byPixels.size(); ++i) {
      EXPECT_EQ(byRects[i].x0, byPixels[i].x0);
      EXPECT_EQ(byRects[i].x1, byPixels[i].x1);
      EXPECT_EQ(byRects[i].y0, byPixels[i].y0);
      EXPECT_EQ(byRects[i].y1, byPixels[i].y1);
    }
  }
}

// A multipart EXR of 3 x 2 pixels: each part (name, data window's top-left corner, channels)
// with every value of channel c of part p set to 10·p + c.
struct TestPart {
  std::string name;
  int x0;
  std::vector<std::string> channels;
};
void writeParts(const std::string& path, const std::vector<TestPart>& parts) {
  std::vector<Imf::Header> headers;
  for (const TestPart& p : parts) {
    Imf::Header h(Imath::Box2i({0, 0}, {5, 1}), Imath::Box2i({p.x0, 0}, {p.x0 + 2, 1}));
    h.setName(p.name);
    h.setType(Imf::SCANLINEIMAGE);
    for (const std::string& c : p.channels) h.channels().insert(c, Imf::Channel(Imf::FLOAT));
    headers.push_back(h);
  }
  Imf::MultiPartOutputFile file(path.c_str(), headers.data(), int(headers.size()));
  for (size_t p = 0; p < parts.size(); ++p) {
    const size_t n = parts[p].channels.size();
    std::vector<float> values(6 * n);
    for (size_t i = 0; i < values.size(); ++i) values[i] = float(10 * p + i % n);
    Imf::FrameBuffer fb;
    const int x0 = parts[p].x0;
    for (size_t c = 0; c < n; ++c)
      fb.insert(parts[p].channels[c],
                Imf::Slice::Make(Imf::FLOAT, values.data() + c, Imath::V2i(x0, 0), 3, 2,
                                 n * sizeof(float), 3 * n * sizeof(float)));
    Imf::OutputPart out(file, int(p));
    out.setFrameBuffer(fb);
    out.writePixels(2);
  }
}

TEST(ExrInput, EveryPartIsReadWhereTheCallerAsksAndTheirNamesStayApart) {
  // The Python module reads a --multipart frame's AOV parts with its beauty. A name an earlier
  // part has is qualified by its part's ("diffuse.R"); each channel keeps its own part's values.
  const std::string path = tmp("parts.exr");
  writeParts(
      path,
      {{"rgba", 0, {"R", "G", "B", "A"}}, {"depth", 0, {"Z"}}, {"diffuse", 0, {"R", "G", "B"}}});
  const Image first = readImage(path);
  EXPECT_EQ(first.channelNames, (std::vector<std::string>{"R", "G", "B", "A"}));
  const Image all = readImage(path, ExrParts::All);
  ASSERT_EQ(all.channelNames, (std::vector<std::string>{"R", "G", "B", "A", "Z", "diffuse.R",
                                                        "diffuse.G", "diffuse.B"}));
  ASSERT_EQ(all.pixels.size(), 6u * 8u);
  // Part p's channel c (in the order written) holds 10p + c.
  const std::vector<float> pixel = {0, 1, 2, 3, 10, 20, 21, 22};
  for (size_t i = 0; i < 6; ++i)
    EXPECT_EQ(
        std::vector<float>(all.pixels.begin() + long(8 * i), all.pixels.begin() + long(8 * i + 8)),
        pixel)
        << "pixel " << i;
  // A part over other pixels (another tool's cropped AOV) is not laid beside part 0: left out,
  // and named for the caller to say so.
  const std::string shifted = tmp("shifted-parts.exr");
  writeParts(shifted, {{"rgba", 0, {"R", "G", "B", "A"}}, {"depth", 3, {"Z"}}});
  const Image partly = readImage(shifted, ExrParts::All);
  EXPECT_EQ(partly.channelNames, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(partly.partsLeftOut,
            (std::vector<std::string>{"part 1 (\"depth\") covers other pixels than part 0"}));
  // A name still taken once qualified: refused rather than one channel hiding the other.
  const std::string twice = tmp("twice-parts.exr");
  writeParts(twice, {{"x", 0, {"R", "y.R"}}, {"y", 0, {"R"}}});
  EXPECT_NE(readError(twice, ExrParts::All)
                .find(twice + ": part 1 (\"y\") has channel \"R\", which an earlier part has as "
                              "\"y.R\" too"),
            std::string::npos);
}

TEST(ExrInput, CompareNamesAFileWithoutRgbChannels) {
  // A depth-only and a luminance image are refused by name, listing their channels, instead of
  // being measured as if their first channels were R, G and B.
  const std::string depth = tmp("depth.exr"), rgb = tmp("rgb.exr");
  writeFlat(depth, 4, 4, {"Z", "N.x", "N.y"}, 1.0f);
  writeFlat(rgb, 4, 4, {"R", "G", "B", "A"}, 1.0f);
  const auto r = runGlint("compare " + depth + " " + rgb);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(depth + ": compare needs R, G and B channels; it has"), std::string::npos)
      << r.output;
  // Layered RGB ("beauty.R", ...) is colour: compared (identical, so rmse 0).
  const std::string layered = tmp("layered.exr");
  writeFlat(layered, 4, 4, {"beauty.R", "beauty.G", "beauty.B"}, 1.0f);
  const auto l = runGlint("compare " + layered + " " + rgb);
  EXPECT_EQ(l.exitCode, 0) << l.output;
}

TEST(ExrInput, NanAndInfinitePixelsAreReportedNotFatal) {
  // A NaN and an infinite image against a finite one: compare reports infinite errors (JSON
  // null), exit 0; a finite image against itself gives 0.
  const std::string nan = tmp("nan.exr"), inf = tmp("inf.exr"), one = tmp("one.exr");
  writeFlat(nan, 4, 4, {"R", "G", "B"}, std::numeric_limits<float>::quiet_NaN());
  writeFlat(inf, 4, 4, {"R", "G", "B"}, std::numeric_limits<float>::infinity());
  writeFlat(one, 4, 4, {"R", "G", "B"}, 1.0f);
  for (const std::string& bad : {nan, inf}) {
    const auto r = runGlint("compare " + bad + " " + one + " --json -");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("\"rmse\": null"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("max_abs   inf"), std::string::npos) << r.output;
  }
  const auto reverse = runGlint("compare " + one + " " + nan);
  EXPECT_EQ(reverse.exitCode, 0) << reverse.output;
}

}  // namespace
}  // namespace glint
