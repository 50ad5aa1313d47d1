// The GPU backend's shared structs are checked where they are declared
// (SP_CHECK_LAYOUT after each struct in shaders/shared/sp_types.h and
// sp_gpu_types.h); including them here keeps the checks in every build of
// the backend.
#pragma once

#include "sp_gpu_types.h"
#include "sp_types.h"
