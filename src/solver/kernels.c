/* kernels.c: the kernels of the step for the plane and for 3D, from one
 * source (kernels.inc, with separable.inc) compiled with the dimension a
 * constant, and their const tables (solver_internal.h). */
#include "solver/solver_internal.h"

#include <stdlib.h>
#include <string.h>

/* The small kernels of kernels.inc are inlined into their loops whatever
 * their size, so that each loop is compiled for its dimension, its weights
 * and its options. */
#if defined(__GNUC__)
#define KINLINE static inline __attribute__((always_inline))
#else
#define KINLINE static inline
#endif

/* Where a point's weights come from (kernels.inc). */
enum { W_LOCATED = 0, W_ELEMENT, W_LIST, W_SEPARABLE };

#define D 2
#define KD(name) name##2
#include "solver/kernels.inc"
#undef D
#undef KD

#define D 3
#define KD(name) name##3
#include "solver/kernels.inc"
#undef D
#undef KD
