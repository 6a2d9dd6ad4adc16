// Tests for libs/motion/src/bvh_writer.cpp and the bundled motion library (scenarios/motions/, made by
// scripts/generate_motions.py, documented in docs/motion-library.md): every clip loads with its
// documented duration and moves as described; writeBvh → parseBvh is exact for every bundled clip
// and for awkward numbers; saveBvhFile writes atomically and reports failures naming the path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "throng/motion/bvh.hpp"
#include "throng/motion/bvh_writer.hpp"

using namespace throng;
namespace fs = std::filesystem;

namespace {

const std::string kMotions = std::string(THRONG_SOURCE_DIR) + "/scenarios/motions/";

/// The motion library as documented in docs/motion-library.md: clip stem → duration [s].
const std::map<std::string, double> kLibrary = {
    {"look", 4.00},     {"idle", 2.00},         {"walk", 1.12},       {"turn", 1.00},
    {"wave", 1.60},     {"call_out", 1.20},     {"look_at", 1.20},    {"nod", 0.80},
    {"point_toward", 1.40}, {"point_down", 1.20}, {"talk", 2.00}};

motion::MotionClip load(const std::string& name) {
  auto r = motion::loadBvhFile(kMotions + name + ".bvh");
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : core::formatAll(r.errors()));
  return r.ok() ? std::move(r).value() : motion::MotionClip{};
}

/// Column of `joint`'s channel `k` (bundled clips: Zrotation Xrotation Yrotation after the root's positions).
std::size_t column(const motion::MotionClip& clip, const std::string& joint, std::size_t k) {
  const int j = clip.findJoint(joint);
  EXPECT_GE(j, 0) << joint;
  return j < 0 ? 0 : clip.joints[static_cast<std::size_t>(j)].firstChannel + k;
}
constexpr std::size_t kZ = 0, kX = 1, kY = 2;  // rotation channels of a non-root joint
constexpr std::size_t kRootY = 5;               // root: X Y Z position, then Z X Y rotation

/// Largest |value| difference of any channel between frames a and b.
float frameDistance(const motion::MotionClip& clip, std::size_t a, std::size_t b) {
  float d = 0.0f;
  for (std::size_t c = 0; c < clip.channelCount; ++c) d = std::max(d, std::fabs(clip.value(a, c) - clip.value(b, c)));
  return d;
}

void expectSameClip(const motion::MotionClip& a, const motion::MotionClip& b) {
  EXPECT_EQ(a.name, b.name);
  ASSERT_EQ(a.joints.size(), b.joints.size());
  for (std::size_t j = 0; j < a.joints.size(); ++j) {
    SCOPED_TRACE(a.joints[j].name);
    EXPECT_EQ(a.joints[j].name, b.joints[j].name);
    EXPECT_EQ(a.joints[j].parent, b.joints[j].parent);
    EXPECT_EQ(a.joints[j].offset, b.joints[j].offset);
    EXPECT_EQ(a.joints[j].channels, b.joints[j].channels);
    EXPECT_EQ(a.joints[j].firstChannel, b.joints[j].firstChannel);
    EXPECT_EQ(a.joints[j].hasEndSite, b.joints[j].hasEndSite);
    if (a.joints[j].hasEndSite) EXPECT_EQ(a.joints[j].endSite, b.joints[j].endSite);
  }
  EXPECT_EQ(a.frameTime, b.frameTime);
  EXPECT_EQ(a.frameCount, b.frameCount);
  EXPECT_EQ(a.channelCount, b.channelCount);
  ASSERT_EQ(a.values.size(), b.values.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    if (a.values[i] != b.values[i] && ++mismatches <= 5) {
      ADD_FAILURE() << "value " << i << ": " << a.values[i] << " != " << b.values[i];
    }
  }
  EXPECT_EQ(mismatches, 0u);
}

/// A fresh, empty directory under the build tree for file tests.
fs::path scratchDir(const std::string& name) {
  const fs::path dir = fs::path(THRONG_BINARY_DIR) / "bvh_writer_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// A small clip in the writer's canonical layout: parsing it and writing it back gives the same text.
constexpr const char* kSmallClipText = R"(HIERARCHY
ROOT hips
{
  OFFSET 0 1 0
  CHANNELS 6 Xposition Yposition Zposition Yrotation Xrotation Zrotation
  JOINT marker
  {
    OFFSET 0.1 0 0
  }
  JOINT spine
  {
    OFFSET 0 0.25 -0.125
    CHANNELS 2 Xrotation Zrotation
    End Site
    {
      OFFSET 0 0.5 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.0333333
0 1 0 0 0 0 10 20
1 1.5 2 3 4 5 11 21
)";

motion::MotionClip smallClip() {
  auto r = motion::parseBvh(kSmallClipText, "tmp/small.bvh");
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : core::formatAll(r.errors()));
  return r.ok() ? std::move(r).value() : motion::MotionClip{};
}

}  // namespace

// ---- the bundled motion library ----------------------------------------------------------------

TEST(MotionLibrary, EveryBundledClipLoadsWithItsDocumentedDuration) {
  const std::vector<std::string> hAnim = {"HumanoidRoot", "sacroiliac", "l_hip",     "l_knee",     "l_ankle", "r_hip",
                                          "r_knee",       "r_ankle",    "vl5",       "skullbase",  "l_shoulder",
                                          "l_elbow",      "l_wrist",    "r_shoulder", "r_elbow",   "r_wrist"};
  for (const auto& [name, duration] : kLibrary) {
    SCOPED_TRACE(name);
    const motion::MotionClip clip = load(name);
    EXPECT_EQ(clip.name, name);
    EXPECT_DOUBLE_EQ(clip.frameTime, 0.04);  // 25 frames per second
    EXPECT_NEAR(clip.duration(), duration, 1e-9);
    ASSERT_EQ(clip.joints.size(), hAnim.size());
    for (std::size_t j = 0; j < hAnim.size(); ++j) EXPECT_EQ(clip.joints[j].name, hAnim[j]);
    EXPECT_EQ(clip.channelCount, 6u + 3u * 15u);
    EXPECT_LT(fs::file_size(kMotions + name + ".bvh"), 40u * 1024u);
  }
  // Every .bvh in scenarios/motions/ is part of the documented library.
  for (const auto& e : fs::directory_iterator(kMotions)) {
    if (e.path().extension() == ".bvh") EXPECT_EQ(kLibrary.count(e.path().stem().string()), 1u) << e.path();
  }
}

TEST(MotionLibrary, ClipsAreSmoothAndGesturesStartAndEndAtRest) {
  for (const auto& [name, duration] : kLibrary) {
    SCOPED_TRACE(name);
    const motion::MotionClip clip = load(name);
    ASSERT_GT(clip.frameCount, 1u);
    // Eased keyframes: no rotation jumps more than 18° between frames, no root move over 2 cm.
    for (std::size_t f = 1; f < clip.frameCount; ++f) {
      for (std::size_t c = 0; c < clip.channelCount; ++c) {
        const float step = std::fabs(clip.value(f, c) - clip.value(f - 1, c));
        ASSERT_LT(step, c < 3 ? 0.02f : 18.0f) << "frame " << f << ", channel " << c;
      }
    }
  }
  // Gestures played once return to the pose they started in (the rest pose, shared by all).
  const motion::MotionClip wave = load("wave");
  for (const std::string name : {"wave", "call_out", "nod", "point_toward", "point_down"}) {
    SCOPED_TRACE(name);
    const motion::MotionClip clip = load(name);
    EXPECT_LT(frameDistance(clip, 0, clip.frameCount - 1), 1e-3f);
    for (std::size_t c = 0; c < clip.channelCount; ++c) EXPECT_NEAR(clip.value(0, c), wave.value(0, c), 1e-3f) << c;
  }
  // talk loops like idle and walk: its last frame is one ordinary step away from its first.
  const motion::MotionClip talk = load("talk");
  EXPECT_LT(frameDistance(talk, talk.frameCount - 1, 0), 8.0f);
}

TEST(MotionLibrary, ClipsMoveAsDocumented) {
  const auto mid = [](const motion::MotionClip& c) { return c.frameCount / 2; };
  {  // turn: the root ends rotated 90° to the left (positive Y), in place.
    const motion::MotionClip c = load("turn");
    EXPECT_NEAR(c.value(0, kRootY), 0.0f, 1e-3f);
    EXPECT_NEAR(c.value(c.frameCount - 1, kRootY), 90.0f, 1e-3f);
    EXPECT_NEAR(c.value(c.frameCount - 1, 0), 0.0f, 1e-3f);
    EXPECT_NEAR(c.value(c.frameCount - 1, 2), 0.0f, 1e-3f);
  }
  {  // wave: right upper arm out to the side, forearm up, elbow angle oscillating.
    const motion::MotionClip c = load("wave");
    EXPECT_LT(c.value(mid(c), column(c, "r_shoulder", kZ)), -80.0f);
    const std::size_t elbow = column(c, "r_elbow", kZ);
    float lo = 0.0f, hi = -180.0f;
    for (std::size_t f = 12; f < 28; ++f) {
      lo = std::min(lo, c.value(f, elbow));
      hi = std::max(hi, c.value(f, elbow));
    }
    EXPECT_GT(hi - lo, 25.0f);
  }
  {  // call_out: both arms forward and folded up to the mouth.
    const motion::MotionClip c = load("call_out");
    for (const std::string side : {"l", "r"}) {
      EXPECT_LT(c.value(mid(c), column(c, side + "_shoulder", kX)), -50.0f) << side;
      EXPECT_LT(c.value(mid(c), column(c, side + "_elbow", kX)), -120.0f) << side;
    }
  }
  {  // look_at: the head turns left and holds to the last frame.
    const motion::MotionClip c = load("look_at");
    EXPECT_GT(c.value(c.frameCount - 1, column(c, "skullbase", kY)), 35.0f);
    EXPECT_NEAR(c.value(c.frameCount - 1, column(c, "skullbase", kY)), c.value(mid(c), column(c, "skullbase", kY)), 1.0f);
  }
  {  // nod: chin down (positive X) early in the clip.
    const motion::MotionClip c = load("nod");
    float peak = 0.0f;
    for (std::size_t f = 0; f < c.frameCount; ++f) peak = std::max(peak, c.value(f, column(c, "skullbase", kX)));
    EXPECT_GT(peak, 12.0f);
  }
  {  // point_toward: the right arm forward at shoulder height, elbow nearly straight.
    const motion::MotionClip c = load("point_toward");
    EXPECT_LT(c.value(mid(c), column(c, "r_shoulder", kX)), -80.0f);
    EXPECT_GT(c.value(mid(c), column(c, "r_elbow", kX)), -5.0f);
  }
  {  // point_down: the right arm forward-down, the head looks down.
    const motion::MotionClip c = load("point_down");
    EXPECT_LT(c.value(mid(c), column(c, "r_shoulder", kX)), -35.0f);
    EXPECT_GT(c.value(mid(c), column(c, "r_shoulder", kX)), -60.0f);
    EXPECT_GT(c.value(mid(c), column(c, "skullbase", kX)), 15.0f);
  }
  {  // talk: forearms raised throughout.
    const motion::MotionClip c = load("talk");
    for (std::size_t f = 0; f < c.frameCount; ++f) EXPECT_LT(c.value(f, column(c, "r_elbow", kX)), -25.0f) << f;
  }
}

// ---- writeBvh ----------------------------------------------------------------------------------

TEST(BvhWriter, EveryBundledClipRoundTripsExactly) {
  for (const auto& [name, duration] : kLibrary) {
    SCOPED_TRACE(name);
    const motion::MotionClip clip = load(name);
    const std::string text = motion::writeBvh(clip);
    auto again = motion::parseBvh(text, "elsewhere/" + name + ".bvh");
    ASSERT_TRUE(again.ok()) << core::formatAll(again.errors());
    expectSameClip(clip, *again);
    EXPECT_EQ(motion::writeBvh(*again), text);  // writing is deterministic and stable
  }
}

TEST(BvhWriter, WritesTheDocumentedLayout) {
  const std::string text = motion::writeBvh(smallClip());
  EXPECT_EQ(text, kSmallClipText);
}

TEST(BvhWriter, AwkwardNumbersRoundTripExactly) {
  motion::MotionClip clip = smallClip();
  const std::vector<float> awkward = {-0.0f, 1e-7f, 123456.789f, 1e9f, -1e9f, 1.17549435e-38f, 3.4028e-30f,
                                      0.1f, 1.0f / 3.0f, -2.0f / 7.0f, 16777217.0f, 0.95f, 1e-45f, 9.99999e8f};
  clip.frameCount = awkward.size();
  clip.values.clear();
  for (std::size_t f = 0; f < clip.frameCount; ++f) {
    for (std::size_t c = 0; c < clip.channelCount; ++c) clip.values.push_back(awkward[(f + c) % awkward.size()] * (c % 2 ? -1.0f : 1.0f));
  }
  clip.frameTime = 1.0 / 30.0;
  clip.joints[2].offset = {1.0f / 3.0f, -1e-6f, 7.25f};
  ASSERT_TRUE(motion::checkMotionClip(clip, "x").ok());
  auto again = motion::parseBvh(motion::writeBvh(clip), "tmp/small.bvh");
  ASSERT_TRUE(again.ok()) << core::formatAll(again.errors());
  expectSameClip(clip, *again);
  EXPECT_EQ(motion::writeBvh(clip).find("-0 "), std::string::npos);  // -0 is written as 0
}

TEST(BvhWriter, CheckReportsClipsThatCannotBeWritten) {
  const motion::MotionClip good = smallClip();
  const core::Status goodStatus = motion::checkMotionClip(good, "out.bvh");
  ASSERT_TRUE(goodStatus.ok()) << core::formatAll(goodStatus.errors());
  const auto firstError = [](const motion::MotionClip& c) {
    auto s = motion::checkMotionClip(c, "out.bvh");
    EXPECT_FALSE(s.ok());
    if (s.ok()) return core::Diagnostic{};
    EXPECT_EQ(s.errors()[0].source, "out.bvh");
    return s.errors()[0];
  };
  motion::MotionClip c = good;
  c.joints[1].name = "two words";
  EXPECT_NE(firstError(c).what.find("\"two words\""), std::string::npos);
  c = good;
  c.joints[2].name = "marker";
  EXPECT_NE(firstError(c).what.find("duplicate joint name \"marker\""), std::string::npos);
  c = good;
  c.values.pop_back();
  EXPECT_NE(firstError(c).what.find("15 values"), std::string::npos);
  c = good;
  c.values[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(firstError(c).what.find("frame 0, channel 3"), std::string::npos);
  c = good;
  c.joints[2].parent = 5;
  EXPECT_NE(firstError(c).expected.find("depth-first"), std::string::npos);
  c = good;
  c.frameTime = 0.0;
  EXPECT_NE(firstError(c).what.find("frame time"), std::string::npos);
  c = good;
  c.joints[2].channels.push_back(motion::MotionChannel::Xrotation);
  EXPECT_NE(firstError(c).what.find("twice"), std::string::npos);
}

// ---- saveBvhFile -------------------------------------------------------------------------------

TEST(BvhWriter, SaveWritesAFileThatLoadsBackAndReplacesAnOldOne) {
  const fs::path dir = scratchDir("save");
  const std::string path = (dir / "wave.bvh").string();
  { std::ofstream(path) << "old contents"; }
  const motion::MotionClip wave = load("wave");
  const core::Status saved = motion::saveBvhFile(path, wave);
  ASSERT_TRUE(saved.ok()) << core::formatAll(saved.errors());
  EXPECT_EQ(filesIn(dir), std::vector<std::string>{"wave.bvh"});  // no temporary file left
  auto loaded = motion::loadBvhFile(path);
  ASSERT_TRUE(loaded.ok()) << core::formatAll(loaded.errors());
  expectSameClip(wave, *loaded);
  const auto perms = fs::status(path).permissions();
  EXPECT_NE(perms & fs::perms::others_read, fs::perms::none);
}

TEST(BvhWriter, SaveToAnUnwritablePathNamesItAndLeavesNoFile) {
  const fs::path dir = scratchDir("unwritable");
  const motion::MotionClip nod = load("nod");

  // A directory that does not exist.
  const std::string missing = (dir / "no_such_dir" / "nod.bvh").string();
  const core::Status s = motion::saveBvhFile(missing, nod);
  ASSERT_FALSE(s.ok());
  ASSERT_EQ(s.errors().size(), 1u);
  EXPECT_EQ(s.errors()[0].source, missing);
  EXPECT_EQ(s.errors()[0].line, 0);
  EXPECT_NE(s.errors()[0].format().find(missing), std::string::npos) << s.errors()[0].format();
  EXPECT_NE(s.errors()[0].what.find("cannot write file"), std::string::npos) << s.errors()[0].format();
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_FALSE(fs::exists(dir / "no_such_dir"));

  // The path is a directory: the rename fails; the directory and its folder are left as they were.
  const fs::path taken = dir / "taken.bvh";
  fs::create_directories(taken / "inside");
  const core::Status t = motion::saveBvhFile(taken.string(), nod);
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.errors()[0].source, taken.string());
  EXPECT_NE(t.errors()[0].what.find("rename"), std::string::npos) << t.errors()[0].format();
  EXPECT_TRUE(fs::is_directory(taken / "inside"));
  EXPECT_EQ(filesIn(dir), std::vector<std::string>{"taken.bvh"});

  // Not a file path at all.
  const core::Status e = motion::saveBvhFile((dir / "").string(), nod);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(filesIn(dir), std::vector<std::string>{"taken.bvh"});

  // A clip that cannot be written: no file either.
  motion::MotionClip broken = nod;
  broken.values.resize(3);
  const std::string brokenPath = (dir / "broken.bvh").string();
  const core::Status b = motion::saveBvhFile(brokenPath, broken);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.errors()[0].source, brokenPath);
  EXPECT_FALSE(fs::exists(brokenPath));
}
