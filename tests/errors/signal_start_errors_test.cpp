// Signals that start on an event (`when`, `delay`, `before`), refused where the scene cannot mean
// them: checked to the character against docs/errors.md.
#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// B1 (brake on the ring) releases over 10 ms from 0.05 s; C1's command waits for it.
const std::string release = "B1 = { table = [[0, 1], [\"0.05*s\", 1], [\"0.06*s\", 0]] }\n";

TEST_F(EngagementCommands, StartOnNoElement) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"B9 slipping\" }\n",
               R"~(scene.toml:23:48: error: 'B9' is no brake or clutch of the model (it has B1, C1); when = "<element> slipping", "<element> stuck", "|slip_<element>| < <speed>" or "omega_<body> > <speed>" (< or >), e.g. when = "C stuck" or when = "|slip_C| < 50*rpm")~");
}
TEST_F(EngagementCommands, StartOnNoState) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"B1 open\" }\n",
               R"~(scene.toml:23:48: error: 'B1 open' is no event a signal can wait for; give when = "<element> slipping", "<element> stuck", "|slip_<element>| < <speed>" or "omega_<body> > <speed>" (< or >), e.g. when = "C stuck" or when = "|slip_C| < 50*rpm")~");
}
TEST_F(EngagementCommands, StartOnAnOpenElement) {
  expect_error("C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"B1 slipping\" }\n",
               R"~(scene.toml:22:48: error: the signal waits for B1, which the scene does not engage, so it never slips or sticks; give B1 a command in [engagement])~");
}
TEST_F(EngagementCommands, StartDelayNegative) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"B1 slipping\", delay = \"-1*ms\" }\n",
               R"~(scene.toml:23:71: error: a delay is not negative; the signal starts at the event or after it)~");
}
TEST_F(EngagementCommands, StartDelayWithoutWhen) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], delay = \"1*ms\" }\n",
               R"~(scene.toml:23:49: error: delay needs when = "<element> slipping", "<element> stuck", "|slip_<element>| < <speed>" or "omega_<body> > <speed>" (< or >), e.g. when = "C stuck" or when = "|slip_C| < 50*rpm")~");
}
TEST_F(EngagementCommands, StartedTableBeforeItsEvent) {
  expect_error(release + "C1 = { table = [[\"-0.01*s\", 0], [\"0.01*s\", 1]], when = \"B1 slipping\" }\n",
               R"~(scene.toml:23:6: error: a signal that starts on an event counts its times from it, but this one changes at -0.01 s; give its times from 0)~");
}
TEST_F(EngagementCommands, StartedConstant) {
  expect_error(release + "C1 = { constant = \"1\", when = \"B1 slipping\" }\n",
               R"~(scene.toml:23:31: error: a constant has nothing to start on an event; give a step, ramp or table)~");
}
TEST_F(EngagementCommands, StartedStepWithBefore) {
  expect_error(release + "C1 = { step = \"1\", at = \"0*s\", before = \"0\", when = \"B1 slipping\" }\n",
               R"~(scene.toml:23:41: error: a step that starts on an event holds its 'before' until its 'at'; give what comes before the event as a table or ramp of its own)~");
}
TEST_F(EngagementCommands, BeforeItselfWaits) {
  expect_error(release + "C1 = { table = [[0, 1]], when = \"B1 slipping\", before = { table = [[0, 0]], when = \"B1 stuck\" } }\n",
               R"~(scene.toml:23:84: error: what a signal is before its event is a signal of time; give it without when)~");
}
TEST_F(EngagementCommands, BeforeOutOfRange) {
  expect_error(release + "C1 = { table = [[0, 1]], when = \"B1 slipping\", before = { ramp = \"100/s\" } }\n",
               R"~(scene.toml:23:6: error: the command of C1 is 10 at t = 0.1 s; an engagement command is from 0 (open) to 1 (fully engaged) over the whole run)~");
}
TEST_F(EngagementCommands, BeforeWithItsOwnDelay) {
  expect_error(release + "C1 = { table = [[0, 1]], when = \"B1 slipping\", before = { table = [[0, 0]], delay = \"1*ms\" } }\n",
               R"~(scene.toml:23:85: error: what a signal is before its event is a signal of time; give it without delay)~");
}
TEST_F(EngagementCommands, StartedCommandOutsideZeroToOne) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 3]], when = \"B1 slipping\" }\n",
               R"~(scene.toml:23:6: error: the command of C1 is 3 at 0.01 s after its start; an engagement command is from 0 (open) to 1 (fully engaged) over the whole run)~");
}
TEST_F(EngagementCommands, StartedSine) {
  expect_documented(scene_error(edited(base_scene(), {{R"(tau_c = { constant = "100*Nm" })",
                                                       R"(tau_c = { sine = "10*Nm", frequency = "5*Hz", when = "B1 slipping" })"}}) +
                                    "\n[engagement]\n" + release,
                                shift_model()),
                    R"~(scene.toml:9:54: error: a sine has no value to hold until an event; start a table of its points instead)~");
}

// Crossings: a speed or a slip passing a value.
TEST_F(EngagementCommands, StartOnNoSpeed) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"tau_c > 5*rad/s\" }\n", 
               R"~(scene.toml:23:48: error: 'tau_c' is no speed a signal can wait for; give when = "<element> slipping", "<element> stuck", "|slip_<element>| < <speed>" or "omega_<body> > <speed>" (< or >), e.g. when = "C stuck" or when = "|slip_C| < 50*rpm")~");
}
TEST_F(EngagementCommands, StartOnSpeedOfNoBody) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"omega_x > 5*rad/s\" }\n", 
               R"~(scene.toml:23:48: error: 'x' is no body of the model (it has c, p, s, r, g); when = "<element> slipping", "<element> stuck", "|slip_<element>| < <speed>" or "omega_<body> > <speed>" (< or >), e.g. when = "C stuck" or when = "|slip_C| < 50*rpm")~");
}
TEST_F(EngagementCommands, StartOnSlipOfNoElement) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"|slip_B9| < 5*rad/s\" }\n", 
               R"~(scene.toml:23:48: error: 'B9' is no brake or clutch of the model (it has B1, C1); when = "<element> slipping", "<element> stuck", "|slip_<element>| < <speed>" or "omega_<body> > <speed>" (< or >), e.g. when = "C stuck" or when = "|slip_C| < 50*rpm")~");
}
TEST_F(EngagementCommands, StartOnSpeedWithoutUnit) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"omega_c > 5\" }\n", 
               R"~(scene.toml:23:48: error: the speed '5' needs a unit of angular speed, e.g. "50*rpm" or "5*rad/s")~");
}
TEST_F(EngagementCommands, StartOnSpeedWithoutValue) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"omega_c >\" }\n", 
               R"~(scene.toml:23:48: error: 'omega_c >' gives no speed to cross; give when = "<element> slipping", "<element> stuck", "|slip_<element>| < <speed>" or "omega_<body> > <speed>" (< or >), e.g. when = "C stuck" or when = "|slip_C| < 50*rpm")~");
}
TEST_F(EngagementCommands, StartOnSlipNotAboveZero) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"|slip_B1| < 0*rpm\" }\n", 
               R"~(scene.toml:23:48: error: a slip's magnitude crosses a speed above 0, not 0 rad/s; for the element's lock-up give when = "B1 stuck")~");
}
TEST_F(EngagementCommands, StartOnSlipOfAnOpenElement) {
  expect_error("C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"|slip_B1| < 5*rpm\" }\n", 
               R"~(scene.toml:22:48: error: the signal waits for the slip of B1, which the scene does not engage, so its runs have no slip of it; give B1 a command in [engagement], or wait for a body's speed (omega_<body>))~");
}
TEST_F(EngagementCommands, StartOnSpeedLeftOutOfOutputs) {
  expect_error(release + "C1 = { table = [[0, 0], [\"0.01*s\", 1]], when = \"omega_s > 5*rad/s\" }\n", 
               R"~(scene.toml:24:48: error: the signal waits for omega_s, which the scene's outputs leave out; add "omega_s" to outputs)~",
               {{"compare_rigid = true", "compare_rigid = true\noutputs = [\"omega_c\"]"}});
}

}  // namespace
}  // namespace pogear::test
