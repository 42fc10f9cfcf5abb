// Options of a fixed count of values (app/option_arity.h): an occurrence with too few or too
// many is refused naming the option, what it got and what it takes, and never takes the next
// option or the scene as one of its values. "--crop 0 10 -o c.exr" was "Could not convert:
// --crop = 0,10,-o,c.exr"; "--crop 0 10 0 5 7" dropped the 7 without a word.
#include "app/option_arity.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"

namespace glint {
namespace {

struct Command {
  CLI::App app{"test", "glint"};
  std::vector<int> crop;
  std::vector<std::string> ray, outputs;
  std::string scene;
  Command() {
    CLI::App* render = app.add_subcommand("render");
    render->add_option("scene", scene);
    render->add_option("-o", outputs);
    takesValues(*render, render->add_option("--crop", crop), 4, ValueKind::Integer, "X0 X1 Y0 Y1")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    CLI::App* validate = app.add_subcommand("validate");
    takesValues(*validate, validate->add_option("--ray", ray), 9, ValueKind::Number,
                "ox oy oz dx dy dz tmin tmax time");
  }
  // The error checkArities gives, or "" after parsing what it returns.
  std::string parse(const std::vector<std::string>& args) {
    try {
      std::vector<std::string> checked = checkArities(app, args);
      std::reverse(checked.begin(), checked.end());
      app.parse(std::move(checked));
      return "";
    } catch (const UsageError& e) {
      return e.what();
    }
  }
};

TEST(OptionArity, TooFewValuesNameTheOptionAndWhatItGot) {
  Command c;
  EXPECT_EQ(c.parse({"render", "--crop", "0", "10", "-o", "c.exr"}),
            "--crop takes 4 integers X0 X1 Y0 Y1, got 2: 0 10");
  EXPECT_EQ(c.parse({"render", "--crop"}), "--crop takes 4 integers X0 X1 Y0 Y1, got 0: none");
  EXPECT_EQ(c.parse({"render", "--crop", "0", "10", "0", "x"}),
            "--crop takes 4 integers X0 X1 Y0 Y1, got 0 10 0 x (\"x\" is not an integer)");
  EXPECT_EQ(c.parse({"validate", "--ray", "0 0 5 0 0 -1 0 inf"}),
            "--ray takes 9 numbers ox oy oz dx dy dz tmin tmax time, got 8: 0 0 5 0 0 -1 0 inf");
}

TEST(OptionArity, AFurtherValueOfItsKindIsRefusedAndTheSceneIsNot) {
  Command c;
  EXPECT_EQ(c.parse({"render", "--crop", "0", "10", "0", "5", "7"}),
            "--crop takes 4 integers X0 X1 Y0 Y1, got 5: 0 10 0 5 7");
  // A scene after the values is the positional it was meant to be.
  ASSERT_EQ(c.parse({"render", "--crop", "0", "10", "0", "5", "s.json", "-o", "c.exr"}), "");
  EXPECT_EQ(c.crop, (std::vector<int>{0, 10, 0, 5}));
  EXPECT_EQ(c.scene, "s.json");
  EXPECT_EQ(c.outputs, std::vector<std::string>{"c.exr"});
}

TEST(OptionArity, EachOccurrenceIsCheckedAndQuotedValuesCount) {
  Command c;
  ASSERT_EQ(c.parse({"render", "--crop", "0 10 0 5", "--crop=1", "2", "3", "4"}), "");
  EXPECT_EQ(c.crop, (std::vector<int>{0, 10, 0, 5, 1, 2, 3, 4}));
  // Eight numbers in all, but the first --crop has two of them.
  EXPECT_EQ(c.parse({"render", "--crop", "0", "10", "--crop", "0", "10", "0", "5", "1", "2"}),
            "--crop takes 4 integers X0 X1 Y0 Y1, got 2: 0 10");
  // Separate arguments and one quoted report line are the same ray; "-1" and "-inf" are values.
  ASSERT_EQ(c.parse({"validate", "--ray", "0", "0", "5", "0", "0", "-1", "0", "inf", "0"}), "");
  EXPECT_EQ(c.ray.size(), 9u);
  EXPECT_EQ(c.ray[5], "-1");
  ASSERT_EQ(c.parse({"validate", "--ray", "0 0 5 0 0 -inf 0 inf 0"}), "");
  EXPECT_EQ(c.ray[5], "-inf");
}

}  // namespace
}  // namespace glint
