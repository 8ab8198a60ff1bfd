#include "lfcam/node/program_output.h"

#include <gtest/gtest.h>

namespace lfcam {
namespace {

TEST(ProgramOutput, FindsWhatIsOnThePathAndNothingElse) {
  EXPECT_EQ(FindOnPath({"sh"}), "sh");
  EXPECT_EQ(FindOnPath({"lfcam-no-such-program", "sh"}), "sh");  // the first one found
  EXPECT_EQ(FindOnPath({"lfcam-no-such-program"}), "");
}

TEST(ProgramOutput, IsTheFirstLineOfWhatTheProgramPrintsWithoutAShell) {
  EXPECT_EQ(FirstLineOfProgram({"printf", "one\\r\\ntwo\\nthree\\n"}), "one");
  // No shell between: the arguments reach the program as they are.
  EXPECT_EQ(FirstLineOfProgram({"printf", "%s", "$HOME; echo *"}), "$HOME; echo *");
  // Standard error is not read; a large output to the end of the pipe does not block it.
  EXPECT_EQ(FirstLineOfProgram({"sh", "-c", "echo warning >&2; echo out"}), "out");
  EXPECT_EQ(FirstLineOfProgram({"sh", "-c", "echo first; head -c 1000000 /dev/zero"}), "first");
  // Not started, failed or silent: nothing.
  EXPECT_FALSE(FirstLineOfProgram({"lfcam-no-such-program"}));
  EXPECT_FALSE(FirstLineOfProgram({"sh", "-c", "echo almost; exit 3"}));
  EXPECT_FALSE(FirstLineOfProgram({"true"}));
  EXPECT_FALSE(FirstLineOfProgram({}));
}

TEST(ProgramOutput, ARunKeepsAllItPrintedAndHowItEnded) {
  const ProgramRun both = RunProgram({"sh", "-c", "echo out; echo err >&2; exit 4"}, true);
  EXPECT_TRUE(both.started);
  EXPECT_EQ(both.exit_status, 4);
  EXPECT_EQ(both.output, "out\nerr\n");
  EXPECT_EQ(RunProgram({"sh", "-c", "echo out; echo err >&2"}).output, "out\n");
  EXPECT_EQ(RunProgram({"sh", "-c", "head -c 200000 /dev/zero"}).output.size(), 200000u);
  const ProgramRun missing = RunProgram({"lfcam-no-such-program", "--help"}, true);
  EXPECT_FALSE(missing.started);
  EXPECT_EQ(missing.output, "");
  EXPECT_EQ(RunProgram({"sh", "-c", "kill -9 $$"}).exit_status, -1);  // killed: no status
}

}  // namespace
}  // namespace lfcam
