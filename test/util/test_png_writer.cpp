#include "surface_nbv/util/png_writer.h"

#include <gtest/gtest.h>

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "surface_nbv/util/cli_args.h"
#include "surface_nbv/util/json_writer.h"

using namespace surface_nbv;

namespace {

std::vector<uint8_t> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

uint32_t be32(const std::vector<uint8_t>& b, size_t at) {
  return (uint32_t(b[at]) << 24) | (uint32_t(b[at + 1]) << 16) | (uint32_t(b[at + 2]) << 8) | b[at + 3];
}

}  // namespace

TEST(PngWriter, WritesDecodableRgbImage) {
  const int w = 7, h = 5;
  std::vector<uint8_t> px(w * h * 3);
  for (size_t i = 0; i < px.size(); ++i) px[i] = static_cast<uint8_t>(i * 13);
  const std::string path = (std::filesystem::temp_directory_path() / "surface_nbv_test.png").string();
  ASSERT_TRUE(writePng(path, w, h, 3, px).ok());
  const std::vector<uint8_t> file = readFile(path);
  ASSERT_GT(file.size(), 45u);
  EXPECT_EQ(file[1], 'P');
  EXPECT_EQ(be32(file, 16), 7u);  // IHDR width
  EXPECT_EQ(be32(file, 20), 5u);  // IHDR height
  EXPECT_EQ(file[25], 2);         // colour type RGB
  // Inflate IDAT and compare with the filtered rows.
  const uint32_t idat_len = be32(file, 33);
  ASSERT_EQ(std::string(file.begin() + 37, file.begin() + 41), "IDAT");
  std::vector<uint8_t> raw(h * (w * 3 + 1));
  uLongf raw_len = raw.size();
  ASSERT_EQ(uncompress(raw.data(), &raw_len, file.data() + 41, idat_len), Z_OK);
  ASSERT_EQ(raw_len, raw.size());
  for (int r = 0; r < h; ++r) {
    EXPECT_EQ(raw[r * (w * 3 + 1)], 0);
    for (int c = 0; c < w * 3; ++c) ASSERT_EQ(raw[r * (w * 3 + 1) + 1 + c], px[r * w * 3 + c]);
  }
  std::filesystem::remove(path);
}

TEST(PngWriter, RefusesBadInput) {
  EXPECT_FALSE(writePng("/tmp/x.png", 0, 5, 1, {}).ok());
  EXPECT_FALSE(writePng("/tmp/x.png", 2, 2, 4, std::vector<uint8_t>(16)).ok());
  EXPECT_FALSE(writePng("/tmp/x.png", 2, 2, 1, std::vector<uint8_t>(3)).ok());
  EXPECT_FALSE(writePng("/nonexistent-dir/x.png", 1, 1, 1, {0}).ok());
}

TEST(ColorizeDepth, NaNIsBlackAndNearDiffersFromFar) {
  const auto rgb = colorizeDepth({NAN, 1.0f, 8.0f}, 1.0f, 8.0f);
  ASSERT_EQ(rgb.size(), 9u);
  EXPECT_EQ(rgb[0] + rgb[1] + rgb[2], 0);
  EXPECT_GT(rgb[3] + rgb[4] + rgb[5], rgb[6] + rgb[7] + rgb[8]);
}

TEST(JsonWriter, NestsAndEscapes) {
  JsonWriter j;
  j.beginObject().value("a", 1).value("s", std::string("q\"\n")).value("nan", NAN);
  j.beginArray("list").value("", 2.5).endArray().endObject();
  const std::string s = j.str();
  EXPECT_NE(s.find("\"a\": 1"), std::string::npos);
  EXPECT_NE(s.find("\"q\\\"\\n\""), std::string::npos);
  EXPECT_NE(s.find("\"nan\": null"), std::string::npos);
  EXPECT_NE(s.find("2.5"), std::string::npos);
  EXPECT_EQ(std::count(s.begin(), s.end(), '{'), std::count(s.begin(), s.end(), '}'));
}

TEST(CliArgs, ParsesOptionsFlagsAndRejectsUnknown) {
  CliArgs args({"scene", "offset", "n"}, {"help"});
  const char* argv[] = {"tool", "--scene", "plant", "--offset=1,2,3", "--help", "--n", "4", "file"};
  ASSERT_TRUE(args.parse(8, const_cast<char**>(argv)).ok());
  EXPECT_EQ(args.get("scene", ""), "plant");
  std::vector<double> v;
  ASSERT_TRUE(args.getDoubles("offset", 3, &v).ok());
  EXPECT_EQ(v, (std::vector<double>{1, 2, 3}));
  int n = 0;
  ASSERT_TRUE(args.getInt("n", &n).ok());
  EXPECT_EQ(n, 4);
  EXPECT_TRUE(args.has("help"));
  EXPECT_EQ(args.positional(), std::vector<std::string>{"file"});
  EXPECT_FALSE(args.getDoubles("offset", 2, &v).ok());

  CliArgs bad({"scene"}, {});
  const char* argv2[] = {"tool", "--sceen", "x"};
  const Status s = bad.parse(3, const_cast<char**>(argv2));
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("--sceen"), std::string::npos);
  CliArgs missing({"scene"}, {});
  const char* argv3[] = {"tool", "--scene"};
  EXPECT_FALSE(missing.parse(2, const_cast<char**>(argv3)).ok());
  CliArgs num({"n"}, {});
  const char* argv4[] = {"tool", "--n", "4x"};
  ASSERT_TRUE(num.parse(3, const_cast<char**>(argv4)).ok());
  double d = 0;
  EXPECT_FALSE(num.getDouble("n", &d).ok());
}

TEST(CliArgs, ParseCommandPrintsHelpOrRefusesPositionalArguments) {
  std::ostringstream out;
  bool help = true;
  CliArgs plain({"n"}, {"help"});
  const char* argv[] = {"tool", "--n", "4"};
  ASSERT_TRUE(plain.parseCommand(3, const_cast<char**>(argv), "usage\n", out, &help).ok());
  EXPECT_FALSE(help);
  EXPECT_TRUE(out.str().empty());
  CliArgs asked({"n"}, {"help"});
  const char* argv2[] = {"tool", "--help", "extra"};
  ASSERT_TRUE(asked.parseCommand(3, const_cast<char**>(argv2), "usage\n", out, &help).ok());
  EXPECT_TRUE(help);
  EXPECT_EQ(out.str(), "usage\n");
  CliArgs stray({"n"}, {"help"});
  const char* argv3[] = {"tool", "file"};
  const Status s = stray.parseCommand(2, const_cast<char**>(argv3), "usage\n", out, &help);
  EXPECT_FALSE(help);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("unexpected argument 'file'"), std::string::npos);
  CliArgs unknown({"n"}, {"help"});
  const char* argv4[] = {"tool", "--m", "1"};
  EXPECT_FALSE(unknown.parseCommand(3, const_cast<char**>(argv4), "usage\n", out, &help).ok());
}
