// The draw pass's shared structs are checked where they are declared
// (SP_CHECK_LAYOUT after each struct in shaders/shared/sp_draw_types.h);
// including them here keeps the checks in every build of the passes.
#pragma once

#include "sp_draw_types.h"
