// The expression-template math module gpusolve::math (thesis 4.2): value and
// Global types for 3-vectors, 3x3 matrices and quaternions, and their operators.
#pragma once

#include "gpusolve/math/elementwise.hpp"
#include "gpusolve/math/expr.hpp"
#include "gpusolve/math/expr_storage.hpp"
#include "gpusolve/math/global.hpp"
#include "gpusolve/math/load.hpp"
#include "gpusolve/math/matrix3x3.hpp"
#include "gpusolve/math/matrix_expr.hpp"
#include "gpusolve/math/matrix_functions.hpp"
#include "gpusolve/math/node.hpp"
#include "gpusolve/math/norm.hpp"
#include "gpusolve/math/quaternion.hpp"
#include "gpusolve/math/quaternion_expr.hpp"
#include "gpusolve/math/rotation.hpp"
#include "gpusolve/math/value.hpp"
#include "gpusolve/math/vector3.hpp"
#include "gpusolve/math/vector_expr.hpp"
