#pragma once
#include "mid/mid.h"
// Reaches low only through mid, which it may not.
#include "low/low.h"
