#pragma once
/// Bit-for-bit comparison of two compensation results (a hole's doubles, its strings, the run's
/// counters): what "the same result" means for the thread-count and block-size tests.
#include <gtest/gtest.h>

#include "compensator/compensation/compensation.hpp"
#include "plugin/api/job.hpp"
#include "tests/support/test_support.hpp"

namespace roprec::test {

inline void expectSameHole(const HoleCompensation& a, const HoleCompensation& b) {
  SCOPED_TRACE(a.id);
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.ok, b.ok);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_TRUE(sameBits(a.psi, b.psi));
  EXPECT_TRUE(sameBits(a.T_programmed.data(), b.T_programmed.data(), 16));
  EXPECT_TRUE(sameBits(a.theta_cmd.data(), b.theta_cmd.data(), 6));
  EXPECT_TRUE(sameBits(a.theta_d.data(), b.theta_d.data(), 6));
  EXPECT_TRUE(sameBits(a.residual.data(), b.residual.data(), 3));
  EXPECT_TRUE(sameBits(a.before.joints.data(), b.before.joints.data(), 6));
  EXPECT_TRUE(sameBits(a.after.U_work_exact, b.after.U_work_exact));
  EXPECT_TRUE(sameBits(a.U_work_keep, b.U_work_keep));
  EXPECT_EQ(a.config_text, b.config_text);
  EXPECT_EQ(a.config_reason, b.config_reason);
  EXPECT_EQ(a.psi_reason, b.psi_reason);
  EXPECT_EQ(a.note, b.note);
  EXPECT_EQ(a.branch, b.branch);
}

inline void expectSameStats(const CompensationStats& a, const CompensationStats& b) {
  EXPECT_EQ(a.dp_nodes, b.dp_nodes);
  EXPECT_EQ(a.infeasible_nodes, b.infeasible_nodes);
  EXPECT_EQ(a.refined, b.refined);
  EXPECT_EQ(a.nlopt_evaluations, b.nlopt_evaluations);
  EXPECT_EQ(a.relaxed_wrist, b.relaxed_wrist);
  EXPECT_EQ(a.psi_changed, b.psi_changed);
  EXPECT_EQ(a.psi_for_jumps, b.psi_for_jumps);
  EXPECT_EQ(a.stiffness_compared, b.stiffness_compared);
  EXPECT_EQ(a.config_changed, b.config_changed);
  EXPECT_TRUE(sameBits(a.U_work_sum, b.U_work_sum));
  EXPECT_TRUE(sameBits(a.jump_threshold_used, b.jump_threshold_used));
}

/// A streamed compensate job against the whole job: the counts, the refusals, whether it may be
/// written, the summary and the statistics, bit for bit.
inline void expectSameJobResult(const api::CompensationResult& a,
                                const api::CompensationResult& whole) {
  EXPECT_EQ(a.hole_count, whole.holes.size());
  EXPECT_EQ(a.failed, whole.failed);
  EXPECT_EQ(a.writable, whole.writable);
  EXPECT_EQ(a.refused, whole.refused);
  EXPECT_EQ(a.summary.error_before_um, whole.summary.error_before_um);
  EXPECT_EQ(a.summary.residual_after_um, whole.summary.residual_after_um);
  EXPECT_EQ(a.summary.conform_before, whole.summary.conform_before);
  EXPECT_EQ(a.summary.conform_after, whole.summary.conform_after);
  EXPECT_EQ(a.summary.jumps_before, whole.summary.jumps_before);
  EXPECT_EQ(a.summary.jumps_after, whole.summary.jumps_after);
  expectSameStats(a.stats, whole.stats);
}

}  // namespace roprec::test
