// Tests for libs/motion/src/bvh_parser.cpp: a valid file's hierarchy and values, every class of error
// with its line:column, the limits, and the bundled clips in scenarios/motions/.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "throng/motion/bvh.hpp"

using namespace throng;
using motion::MotionChannel;

namespace {

/// 1-based line:column of the `nth` occurrence of `needle` in `text` (ASCII: columns count bytes).
std::pair<int, int> posOf(const std::string& text, const std::string& needle, std::size_t nth = 0) {
  std::size_t at = text.find(needle);
  for (std::size_t k = 0; k < nth && at != std::string::npos; ++k) at = text.find(needle, at + 1);
  EXPECT_NE(at, std::string::npos) << needle;
  int line = 1, col = 1;
  for (std::size_t i = 0; i < at && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

const char* kClip = R"(HIERARCHY
ROOT hips
{
  OFFSET 0 1 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT spine
  {
    OFFSET 0 0.2 0
    CHANNELS 3 Yrotation Xrotation Zrotation
    End Site
    {
      OFFSET 0 0.5 0
    }
  }
  JOINT leg
  {
    OFFSET 0.1 -0.1 0
    CHANNELS 1 Xrotation
  }
}
MOTION
Frames: 2
Frame Time: 0.5
0 1 0 0 0 0 10 20 30 5
1 1.5 2 3 4 5 11 21 31 -5
)";

std::string edit(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

core::Diagnostics errorsOf(const std::string& text) {
  auto r = motion::parseBvh(text, "t.bvh");
  EXPECT_FALSE(r.ok()) << "expected errors for:\n" << text;
  return r.ok() ? core::Diagnostics{} : r.errors();
}

/// The only diagnostic of `text`, which must be at `needle`.
core::Diagnostic onlyErrorAt(const std::string& text, const std::string& needle, std::size_t nth = 0) {
  const auto ds = errorsOf(text);
  EXPECT_EQ(ds.size(), 1u) << core::formatAll(ds);
  if (ds.empty()) return {};
  const auto [line, col] = posOf(text, needle, nth);
  EXPECT_EQ(ds[0].source, "t.bvh");
  EXPECT_EQ(ds[0].line, line) << ds[0].format();
  EXPECT_EQ(ds[0].column, col) << ds[0].format();
  return ds[0];
}

std::string bundled(const std::string& name) { return std::string(THRONG_SOURCE_DIR) + "/scenarios/motions/" + name; }

}  // namespace

TEST(BvhParser, ReadsHierarchyChannelsAndValues) {
  auto r = motion::parseBvh(kClip, "motions/demo.bvh");
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const motion::MotionClip& clip = *r;
  EXPECT_EQ(clip.name, "demo");
  ASSERT_EQ(clip.joints.size(), 3u);
  EXPECT_EQ(clip.joints[0].name, "hips");
  EXPECT_EQ(clip.joints[0].parent, -1);
  EXPECT_EQ(clip.joints[1].name, "spine");
  EXPECT_EQ(clip.joints[1].parent, 0);
  EXPECT_EQ(clip.joints[2].name, "leg");
  EXPECT_EQ(clip.joints[2].parent, 0);
  EXPECT_FLOAT_EQ(clip.joints[0].offset[1], 1.0f);
  EXPECT_FLOAT_EQ(clip.joints[2].offset[0], 0.1f);
  EXPECT_FLOAT_EQ(clip.joints[2].offset[1], -0.1f);
  EXPECT_TRUE(clip.joints[1].hasEndSite);
  EXPECT_FLOAT_EQ(clip.joints[1].endSite[1], 0.5f);
  EXPECT_FALSE(clip.joints[2].hasEndSite);
  // Channels keep file order; columns tile the row.
  ASSERT_EQ(clip.joints[1].channels.size(), 3u);
  EXPECT_EQ(clip.joints[1].channels[0], MotionChannel::Yrotation);
  EXPECT_EQ(clip.joints[1].channels[2], MotionChannel::Zrotation);
  EXPECT_EQ(motion::channelName(clip.joints[1].channels[1]), "Xrotation");
  EXPECT_EQ(clip.joints[0].firstChannel, 0u);
  EXPECT_EQ(clip.joints[1].firstChannel, 6u);
  EXPECT_EQ(clip.joints[2].firstChannel, 9u);
  EXPECT_EQ(clip.channelCount, 10u);
  EXPECT_EQ(clip.frameCount, 2u);
  EXPECT_DOUBLE_EQ(clip.frameTime, 0.5);
  EXPECT_DOUBLE_EQ(clip.duration(), 1.0);
  ASSERT_EQ(clip.values.size(), 20u);
  EXPECT_FLOAT_EQ(clip.value(0, 1), 1.0f);
  EXPECT_FLOAT_EQ(clip.value(1, 1), 1.5f);
  EXPECT_FLOAT_EQ(clip.value(1, 8), 31.0f);
  EXPECT_FLOAT_EQ(clip.value(1, 9), -5.0f);
  EXPECT_EQ(clip.findJoint("leg"), 2);
  EXPECT_EQ(clip.findJoint("arm"), -1);
}

TEST(BvhParser, AcceptsCrlfTabsBlankLinesAndPlusSigns) {
  std::string text;
  for (const char c : std::string(kClip)) {
    if (c == '\n') text += "\r\n";
    else if (c == ' ') text += '\t';
    else text += c;
  }
  text = edit(text, "Frame\tTime:", "Frame Time:");
  text = edit(text, "0\t1\t0\t0\t0\t0\t10", "0\t+1\t0\t0\t0\t0\t10");
  text += "\r\n\r\n";
  auto r = motion::parseBvh(text, "t.bvh");
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_FLOAT_EQ(r->value(0, 1), 1.0f);
  EXPECT_EQ(r->frameCount, 2u);
}

TEST(BvhParser, MisspelledKeywordNamesWhatWasExpected) {
  const std::string text = edit(kClip, "OFFSET 0 0.2 0", "OFSET 0 0.2 0");
  const auto d = onlyErrorAt(text, "OFSET");
  EXPECT_EQ(d.what, "found \"OFSET\"");
  EXPECT_EQ(d.expected, "\"OFFSET\" followed by 3 numbers");
  EXPECT_EQ(d.format(), "t.bvh:8:5: found \"OFSET\"; expected \"OFFSET\" followed by 3 numbers (did you mean \"OFFSET\"?)");

  const std::string joint = edit(kClip, "JOINT leg", "JIONT leg");
  const auto j = onlyErrorAt(joint, "JIONT");
  EXPECT_TRUE(contains(j.expected, "\"JOINT\", \"End Site\" or \"}\"")) << j.format();
  EXPECT_EQ(j.hint, "did you mean \"JOINT\"?");

  const auto h = onlyErrorAt(edit(kClip, "HIERARCHY", "HIERARCHIE"), "HIERARCHIE");
  EXPECT_TRUE(contains(h.expected, "\"HIERARCHY\"")) << h.format();
  const auto m = onlyErrorAt(edit(kClip, "MOTION", "MOTON"), "MOTON");
  EXPECT_TRUE(contains(m.expected, "\"MOTION\"")) << m.format();
}

TEST(BvhParser, OffsetWithTooFewNumbers) {
  const std::string text = edit(kClip, "OFFSET 0 0.2 0\n", "OFFSET 0 0.2\n");
  const auto d = onlyErrorAt(text, "CHANNELS 3");
  EXPECT_EQ(d.what, "OFFSET has 2 numbers");
  EXPECT_EQ(d.expected, "\"OFFSET\" followed by 3 numbers");
}

TEST(BvhParser, FrameRowWithWrongNumberOfValues) {
  const std::string few = edit(kClip, "1 1.5 2 3 4 5 11 21 31 -5", "1 1.5 2 3 4 5 11 21 31");
  const auto d = onlyErrorAt(few, "\n", 24);  // the end of that row (line 25)
  EXPECT_EQ(d.line, 25);
  EXPECT_EQ(d.what, "frame 2 has 9 values");
  EXPECT_EQ(d.expected, "10 numbers (one per channel)");

  const std::string many = edit(kClip, "0 1 0 0 0 0 10 20 30 5", "0 1 0 0 0 0 10 20 30 5 7");
  const auto m = onlyErrorAt(many, "7\n");
  EXPECT_EQ(m.what, "frame 1 has more than 10 values");
}

TEST(BvhParser, EveryBadRowIsReported) {
  std::string text = edit(kClip, "0 1 0 0 0 0 10 20 30 5", "0 1 0 0 0 0 10 20 30");
  text = edit(text, "1 1.5 2 3 4 5 11 21 31 -5", "1 1.5 2 3 4 5 11 21 x -5");
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 2u) << core::formatAll(ds);
  EXPECT_EQ(ds[0].line, 24);
  EXPECT_EQ(ds[1].line, 25);
  EXPECT_EQ(ds[1].column, posOf(text, "x -5").second);
  EXPECT_EQ(ds[1].what, "found \"x\"");
  EXPECT_EQ(ds[1].expected, "a finite number (frame 2, channel 9)");
}

TEST(BvhParser, FrameTimeMustBePositive) {
  for (const char* bad : {"0", "-0.04", "61"}) {
    const std::string text = edit(kClip, "Frame Time: 0.5", std::string("Frame Time: ") + bad);
    const auto ds = errorsOf(text);
    ASSERT_EQ(ds.size(), 1u) << core::formatAll(ds);
    const auto& d = ds[0];
    EXPECT_EQ(d.line, 23);
    EXPECT_EQ(d.column, 13);
    EXPECT_TRUE(contains(d.what, "out of range")) << d.format();
    EXPECT_EQ(d.expected, "a frame time > 0 and <= 60 s");
  }
}

TEST(BvhParser, FramesCountMustMatchRows) {
  const std::string fewer = edit(kClip, "Frames: 2", "Frames: 3");
  const auto d = onlyErrorAt(fewer, "3\nFrame Time");
  EXPECT_EQ(d.what, "\"Frames: 3\" but the file has 2 frame rows");

  const std::string more = edit(kClip, "Frames: 2", "Frames: 1");
  const auto m = onlyErrorAt(more, "1 1.5 2");
  EXPECT_EQ(m.what, "more frame rows than \"Frames: 1\"");

  for (const char* bad : {"0", "1000001", "two", "-1", "99999999999999999999999"}) {
    const std::string text = edit(kClip, "Frames: 2", std::string("Frames: ") + bad);
    const auto e = onlyErrorAt(text, std::string(bad) + "\nFrame Time");
    EXPECT_EQ(e.column, 9) << e.format();
    EXPECT_EQ(e.expected, "a whole number of frames from 1 to 1000000") << e.format();
  }
}

TEST(BvhParser, UnknownChannelNameSuggestsTheClosest) {
  const std::string text = edit(kClip, "CHANNELS 1 Xrotation", "CHANNELS 1 Xrot");
  const auto d = onlyErrorAt(text, "Xrot\n");
  EXPECT_EQ(d.what, "unknown channel \"Xrot\"");
  EXPECT_TRUE(contains(d.expected, "Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation"));
  EXPECT_EQ(d.hint, "did you mean \"Xrotation\"?");

  const auto twice = onlyErrorAt(edit(kClip, "CHANNELS 3 Yrotation Xrotation Zrotation", "CHANNELS 3 Yrotation Xrotation Yrotation"),
                                 "Yrotation", 2);
  EXPECT_TRUE(contains(twice.what, "listed twice")) << twice.format();
  const auto seven = onlyErrorAt(edit(kClip, "CHANNELS 1 Xrotation", "CHANNELS 7 Xrotation"), "7 Xrotation");
  EXPECT_EQ(seven.expected, "a channel count from 0 to 6 after \"CHANNELS\"");
  const auto short_ = onlyErrorAt(edit(kClip, "CHANNELS 1 Xrotation", "CHANNELS 2 Xrotation"), "}\n}\nMOTION");
  EXPECT_EQ(short_.what, "CHANNELS declares 2 channels but lists 1");
}

TEST(BvhParser, NonFiniteAndHugeNumbersAreRejected) {
  const auto nan = onlyErrorAt(edit(kClip, "10 20 30 5", "10 nan 30 5"), "nan");
  EXPECT_EQ(nan.what, "number \"nan\" is not finite");
  const auto inf = onlyErrorAt(edit(kClip, "OFFSET 0.1 -0.1 0", "OFFSET 0.1 -inf 0"), "-inf");
  EXPECT_EQ(inf.what, "number \"-inf\" is not finite");
  const auto big = onlyErrorAt(edit(kClip, "OFFSET 0 1 0", "OFFSET 0 1e999 0"), "1e999");
  EXPECT_EQ(big.what, "number \"1e999\" is not finite");
  const auto large = onlyErrorAt(edit(kClip, "11 21 31", "11 2e9 31"), "2e9");
  EXPECT_EQ(large.what, "number \"2e9\" is out of range");
  const auto time = onlyErrorAt(edit(kClip, "Frame Time: 0.5", "Frame Time: nan"), "nan");
  EXPECT_EQ(time.expected, "a frame time > 0 and <= 60 s");
}

TEST(BvhParser, TooDeepHierarchy) {
  std::string text = "HIERARCHY\nROOT r\n{\n OFFSET 0 0 0\n CHANNELS 1 Xrotation\n";
  for (int i = 0; i < 70; ++i) text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 0 0\n";
  const auto d = onlyErrorAt(text, "JOINT j64\n");
  EXPECT_EQ(d.what, "hierarchy nested deeper than 64 joints");
  EXPECT_EQ(d.expected, "at most 64 levels of JOINT below ROOT");
}

TEST(BvhParser, TooManyJoints) {
  std::string text = "HIERARCHY\nROOT r\n{\n OFFSET 0 0 0\n CHANNELS 1 Xrotation\n";
  for (int i = 1; i <= 1030; ++i) text += "JOINT j" + std::to_string(i) + " { OFFSET 0 0 0 }\n";
  text += "}\nMOTION\nFrames: 1\nFrame Time: 1\n0\n";
  const auto d = onlyErrorAt(text, "JOINT j1024 ");
  EXPECT_EQ(d.what, "more than 1024 joints");
}

TEST(BvhParser, StructuralErrors) {
  const auto empty = errorsOf("");
  ASSERT_EQ(empty.size(), 1u);
  EXPECT_EQ(empty[0].format(), "t.bvh:1:1: found the end of the file; expected \"HIERARCHY\" at the start of a BVH file");

  const auto dup = onlyErrorAt(edit(kClip, "JOINT leg", "JOINT spine"), "spine", 1);
  EXPECT_EQ(dup.what, "duplicate joint name \"spine\"");

  const auto noName = onlyErrorAt(edit(kClip, "JOINT leg\n", "JOINT\n"), "{\n    OFFSET 0.1");
  EXPECT_EQ(noName.expected, "a joint name");

  const auto spaced = onlyErrorAt(edit(kClip, "JOINT leg", "JOINT left leg"), "leg\n");
  EXPECT_TRUE(contains(spaced.expected, "joint names contain no spaces")) << spaced.format();

  const auto twoRoots = onlyErrorAt(edit(kClip, "MOTION", "ROOT b { OFFSET 0 0 0 }\nMOTION"), "ROOT b");
  EXPECT_EQ(twoRoots.what, "a second ROOT");

  const auto junk = onlyErrorAt(edit(kClip, "Frame Time: 0.5", "Frame Time: 0.5 fps"), "fps");
  EXPECT_EQ(junk.what, "found \"fps\" after the frame time");

  const auto noChannels = onlyErrorAt(
      "HIERARCHY\nROOT r\n{\n OFFSET 0 0 0\n}\nMOTION\nFrames: 1\nFrame Time: 1\n\n", "ROOT");
  EXPECT_EQ(noChannels.what, "the hierarchy declares no channels");

  const auto truncated = errorsOf(std::string(kClip).substr(0, 120));
  ASSERT_EQ(truncated.size(), 1u);
  EXPECT_GT(truncated[0].line, 0);
}

TEST(BvhParser, ColumnsCountCodePoints) {
  const std::string text = edit(kClip, "JOINT leg", "JOINT é_leg OFSET");
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].line, 15);
  EXPECT_EQ(ds[0].column, 15);  // "  JOINT é_leg OFSET": é is one column (two bytes)
  EXPECT_EQ(ds[0].what, "found \"OFSET\"");
}

TEST(BvhParser, FileLimitAndMissingFile) {
  const std::string huge(motion::kMaxBvhBytes + 1, ' ');
  const auto ds = errorsOf(huge);
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].expected, "at most 67108864 bytes (64 MiB)");

  auto missing = motion::loadBvhFile(bundled("nope.bvh"));
  ASSERT_FALSE(missing.ok());
  ASSERT_EQ(missing.errors().size(), 1u);
  EXPECT_EQ(missing.errors()[0].line, 0);
  EXPECT_TRUE(contains(missing.errors()[0].what, "cannot open file")) << missing.errors()[0].format();

  auto dir = motion::loadBvhFile(std::string(THRONG_SOURCE_DIR) + "/scenarios/motions");
  ASSERT_FALSE(dir.ok());
  EXPECT_TRUE(contains(dir.errors()[0].what, "not a regular file")) << dir.errors()[0].format();
}

TEST(BvhParser, BundledClipsLoadWithTheirDurations) {
  const std::vector<std::string> hAnim = {"HumanoidRoot", "sacroiliac", "l_hip",      "l_knee",  "l_ankle",   "r_hip",
                                          "r_knee",       "r_ankle",    "vl5",        "skullbase", "l_shoulder", "l_elbow",
                                          "l_wrist",      "r_shoulder", "r_elbow",    "r_wrist"};
  const std::vector<std::pair<std::string, double>> clips = {{"look", 4.0}, {"idle", 2.0}, {"walk", 1.12}};
  for (const auto& [name, duration] : clips) {
    SCOPED_TRACE(name);
    auto r = motion::loadBvhFile(bundled(name + ".bvh"));
    ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
    EXPECT_EQ(r->name, name);
    EXPECT_NEAR(r->duration(), duration, 1e-9);
    ASSERT_EQ(r->joints.size(), hAnim.size());
    for (const auto& joint : hAnim) EXPECT_GE(r->findJoint(joint), 0) << joint;
    EXPECT_EQ(r->channelCount, 6u + 3u * 15u);
  }
}

TEST(BvhParser, BundledClipsMoveAsDescribed) {
  // look: head turns left (positive Y rotation of skullbase) and back; neutral at both ends.
  auto look = motion::loadBvhFile(bundled("look.bvh"));
  ASSERT_TRUE(look.ok());
  const auto& head = look->joints[static_cast<std::size_t>(look->findJoint("skullbase"))];
  const std::size_t yaw = head.firstChannel + 2;  // Zrotation Xrotation Yrotation
  EXPECT_EQ(head.channels[2], MotionChannel::Yrotation);
  EXPECT_NEAR(look->value(0, yaw), 0.0f, 0.5f);
  EXPECT_NEAR(look->value(look->frameCount - 1, yaw), 0.0f, 1.0f);
  EXPECT_GT(look->value(look->frameCount / 2, yaw), 25.0f);

  // walk: the hips swing in antiphase, half a cycle apart.
  auto walk = motion::loadBvhFile(bundled("walk.bvh"));
  ASSERT_TRUE(walk.ok());
  const std::size_t lHip = walk->joints[static_cast<std::size_t>(walk->findJoint("l_hip"))].firstChannel + 1;
  const std::size_t rHip = walk->joints[static_cast<std::size_t>(walk->findJoint("r_hip"))].firstChannel + 1;
  const std::size_t half = walk->frameCount / 2;
  EXPECT_LT(walk->value(0, lHip), -10.0f);  // left leg forward at heel strike
  EXPECT_GT(walk->value(0, rHip), 10.0f);
  EXPECT_NEAR(walk->value(0, lHip), walk->value(half, rHip), 0.01f);
  EXPECT_NEAR(walk->value(half, lHip), walk->value(0, rHip), 0.01f);
}
