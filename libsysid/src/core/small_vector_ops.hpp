// Serial N_Vector operations specialised for CVODE's tiny systems (1 to 4 states).
//
// CVODE does its bookkeeping with vector operations: a step of order q costs q(q+1)/2 linear
// sums for the prediction alone, plus weighted norms, scalings and the nonlinear solver's sums.
// With 2 states each operation is a handful of flops behind three calls (the generic
// dispatcher, the serial operation, its special-case helper), and they took about a third of
// the simulator batch's profile. These replace the serial operations with one function per
// operation and a loop of fixed length, for the operations that showed in the profile. CVODES
// keeps one such vector per sensitivity parameter and works on them with the vector-array
// operations (N_VScaleVectorArray, N_VScaleAddMultiVectorArray, ...): those are replaced too.
//
// Results are bit-identical to the serial ones: the same products and sums in the same order,
// including N_VLinearSum_Serial's special cases that round differently from a x + b y
// (a = b: a (x + y); a = -b: a (x - y)). A test compares them bit for bit.
#ifndef SYSID_SRC_CORE_SMALL_VECTOR_OPS_HPP_
#define SYSID_SRC_CORE_SMALL_VECTOR_OPS_HPP_

#include <nvector/nvector_serial.h>

namespace sysid::internal {

/// Installs the fixed-length operations on serial vector `v` when its length is 1 to 4
/// (vectors cloned from it afterwards inherit them: call before CVodeInit). Returns false, and
/// leaves `v` as it is, for other lengths.
bool UseSmallVectorOps(N_Vector v);

}  // namespace sysid::internal

#endif  // SYSID_SRC_CORE_SMALL_VECTOR_OPS_HPP_
