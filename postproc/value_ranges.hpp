#pragma once
/// Plausibility ranges for the numbers a robot program states (docs/programs.md §16).
///
/// A reader accepts any number the dialect's syntax allows; a corrupted or mistyped value
/// (`Z 1e300`, `B 1e300`, a zero quaternion) would then move a hole, a retract or a frame by an
/// absurd amount without a word. `checkValueRanges` runs after every reader and refuses, with the
/// file and line of the number, what places the robot — the targets a motion moves to (a point no
/// motion uses, such as a placeholder in a KRL .dat, places nothing and is not checked), the
/// frames motions use, motion offsets and speeds:
///   - positions (targets, frames, offsets): |x| ≤ 100 m (100,000 mm);
///   - Euler angles (KUKA A,B,C; FANUC W,P,R; RoboDK rx,ry,rz): |a| ≤ 720 deg;
///   - quaternions: norm within [0.9, 1.1] (RAPID itself refuses a quaternion that is not
///     normalised; roprec normalises the small rounding of exported programs);
///   - joint values (deg, or mm for a linear axis): |q| ≤ 100,000;
///   - external axes: |e| ≤ 100,000, or exactly 9E+09 (RAPID's "axis not used");
///   - configuration numbers (ABB cf1/cf4/cf6/cfx): |cf| ≤ 1000;
///   - linear motion speeds: > 0 and ≤ 10,000 mm/s (10 m/s, beyond every industrial arm's TCP
///     speed; at 0 the motion would not move).
/// Values a program states by name or expression are checked when roprec could evaluate them.

#include <exception>

#include "postproc/program.hpp"

namespace roprec::postproc {

/// Throws InputError(file, line, what is out of range + the accepted range) at the first value
/// outside its range.
void checkValueRanges(const Program& p);

/// The first error of each kind checkValueRanges checks, in its order: targets, frames, motions.
struct RangeErrors {
  std::exception_ptr target, frame, motion;
  /// Throws the error checkValueRanges would throw of the values checked: the first target's,
  /// else the first frame's, else the first motion's; nothing when there is none.
  void rethrow() const;
};
/// checkValueRanges of a part of a program read by windows (ProgramStream): the first error of
/// each kind kept in `first` (one already kept stays) instead of thrown.
void checkValueRanges(const Program& p, RangeErrors& first);

}  // namespace roprec::postproc
