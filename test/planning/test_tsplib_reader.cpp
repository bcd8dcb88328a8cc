#include "surface_nbv/planning/tsplib_reader.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "surface_nbv/planning/lin_kernighan_solver.h"

using namespace surface_nbv;
namespace fs = std::filesystem;

class TsplibReader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("surface_nbv_tsplib_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  // The message of a refused file; fails the test if the file was accepted.
  std::string refusal(const std::string& text) {
    TsplibProblem p;
    const Status s = readTsplib(write("bad.tsp", text), &p);
    EXPECT_FALSE(s.ok()) << text;
    return s.message();
  }
  fs::path dir_;
};

TEST_F(TsplibReader, ReadsAtspFullMatrix) {
  TsplibProblem p;
  const Status s = readTsplib(write("a.atsp",
                                    "NAME: tiny\nTYPE: ATSP\nCOMMENT: test\nDIMENSION: 3\n"
                                    "EDGE_WEIGHT_TYPE: EXPLICIT\nEDGE_WEIGHT_FORMAT: FULL_MATRIX\n"
                                    "EDGE_WEIGHT_SECTION\n9999 1 50\n50 9999\n1\n1 50 9999\nEOF\n"),
                              &p);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(p.name, "tiny");
  EXPECT_EQ(p.type, "ATSP");
  ASSERT_EQ(p.costs.size(), 3);
  EXPECT_EQ(p.costs(0, 0), 0.0);
  EXPECT_EQ(p.costs(0, 1), 1.0);
  EXPECT_EQ(p.costs(1, 2), 1.0);
  EXPECT_EQ(p.costs(2, 0), 1.0);
  EXPECT_EQ(LinKernighanSolver().solve(p.costs).cost, 3.0);
}

TEST_F(TsplibReader, ReadsEuc2dWithRounding) {
  TsplibProblem p;
  const Status s = readTsplib(write("e.tsp",
                                    "NAME : sq\nTYPE : TSP\nDIMENSION : 4\nEDGE_WEIGHT_TYPE : EUC_2D\n"
                                    "NODE_COORD_SECTION\n1 0 0\n2 10 0\n3 10 10\n4 0 10.4\nEOF\n"),
                              &p);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(p.costs(0, 1), 10.0);
  EXPECT_EQ(p.costs(0, 2), 14.0);  // nint(14.142)
  EXPECT_EQ(p.costs(3, 0), 10.0);  // nint(10.4)
  EXPECT_EQ(LinKernighanSolver().solve(p.costs).cost, 40.0);
}

TEST_F(TsplibReader, RefusesMalformedFilesNamingTheLine) {
  const std::string head = "NAME: x\nTYPE: ATSP\nDIMENSION: 2\nEDGE_WEIGHT_TYPE: EXPLICIT\n";
  const std::string full = head + "EDGE_WEIGHT_FORMAT: FULL_MATRIX\nEDGE_WEIGHT_SECTION\n";
  EXPECT_NE(refusal(full + "0 1\n2 zz\n").find(":8: expected a number"), std::string::npos);
  EXPECT_NE(refusal(head + "EDGE_WEIGHT_FORMAT: UPPER_ROW\n").find(":5: EDGE_WEIGHT_FORMAT 'UPPER_ROW'"),
            std::string::npos);
  EXPECT_NE(refusal(head + "EDGE_WEIGHT_FORMAT: FULL_MATRIX\nEDGE_WEIGHT_SECTION\n0 1\n2\n").find("has 3 numbers"),
            std::string::npos);
  EXPECT_NE(refusal(full + "0 1\n2 0 7\n").find(":8: EDGE_WEIGHT_SECTION has 5"), std::string::npos);
  EXPECT_NE(refusal(head + "EDGE_WEIGHT_FORMAT: FULL_MATRIX\nEDGE_WEIGHT_SECTION\n0 -1\n2 0\n").find(":7: negative"),
            std::string::npos);
  EXPECT_NE(refusal("NAME: x\nTYPE: HCP\n").find(":2: TYPE 'HCP'"), std::string::npos);
  EXPECT_NE(refusal("TYPE: TSP\nDIMENSION: -3\n").find(":2: DIMENSION"), std::string::npos);
  EXPECT_NE(refusal("TYPE: TSP\nDIMENSION: 2\nEDGE_WEIGHT_TYPE: GEO\n").find(":3: EDGE_WEIGHT_TYPE 'GEO'"),
            std::string::npos);
  EXPECT_NE(refusal("TYPE: TSP\nFOO: 1\n").find(":2: unknown keyword 'FOO'"), std::string::npos);
  EXPECT_NE(refusal("TYPE: TSP\nDIMENSION: 2\nEDGE_WEIGHT_TYPE: EUC_2D\nNODE_COORD_SECTION\n1 0 0\n1 3 4\n")
                .find(":6: node index"),
            std::string::npos);
  EXPECT_NE(refusal("TYPE: TSP\nDIMENSION: 2\nEDGE_WEIGHT_TYPE: EXPLICIT\nEDGE_WEIGHT_FORMAT: FULL_MATRIX\n"
                    "EDGE_WEIGHT_SECTION\n0 1\n2 0\n")
                .find("not symmetric"),
            std::string::npos);
  EXPECT_NE(refusal("TYPE: TSP\nEDGE_WEIGHT_SECTION\n").find(":2: EDGE_WEIGHT_SECTION before DIMENSION"),
            std::string::npos);
  EXPECT_NE(refusal("").find("no TYPE"), std::string::npos);
  TsplibProblem p;
  EXPECT_NE(readTsplib((dir_ / "missing.tsp").string(), &p).message().find("cannot open"), std::string::npos);
}

TEST_F(TsplibReader, TspSolveTool) {
  // tsp_solve is built next to the test executables (devel/lib/surface_nbv).
  const std::string exe = (fs::read_symlink("/proc/self/exe").parent_path() / "tsp_solve").string();
  if (!fs::exists(exe)) GTEST_SKIP() << exe << " not built";
  const std::string file = write("t.atsp",
                                 "NAME: t\nTYPE: ATSP\nDIMENSION: 3\nEDGE_WEIGHT_TYPE: EXPLICIT\n"
                                 "EDGE_WEIGHT_FORMAT: FULL_MATRIX\nEDGE_WEIGHT_SECTION\n0 1 9\n9 0 1\n1 9 0\n");
  const std::string out = (dir_ / "out.txt").string();
  EXPECT_EQ(std::system((exe + " " + file + " --seed 3 > " + out).c_str()), 0);
  std::ifstream in(out);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\ntour_length: 3\n"), std::string::npos) << text;
  EXPECT_EQ(WEXITSTATUS(std::system((exe + " " + file + " --bogus 1 2>/dev/null").c_str())), 2);
  EXPECT_EQ(WEXITSTATUS(std::system((exe + " " + file + ".missing 2>/dev/null").c_str())), 2);
}

// Found by review and reproduced with fuzz/fuzz_tsplib: a DIMENSION alone
// used to allocate n^2 doubles, and far coordinates gave infinite costs.
TEST_F(TsplibReader, RefusesBeforeAllocatingAndRefusesInfiniteDistances) {
  EXPECT_NE(refusal("TYPE: TSP\nDIMENSION: 100000\nEDGE_WEIGHT_TYPE: EUC_2D\nNODE_COORD_SECTION\n1 0 0\nEOF\n")
                .find("NODE_COORD_SECTION has 3 numbers"),
            std::string::npos);
  EXPECT_NE(refusal("TYPE: TSP\nDIMENSION: 2\nEDGE_WEIGHT_TYPE: EUC_2D\nNODE_COORD_SECTION\n1 -1e308 0\n2 1e308 0\nEOF\n")
                .find("farther apart"),
            std::string::npos);
}
