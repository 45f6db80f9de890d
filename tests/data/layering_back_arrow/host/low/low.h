#pragma once
#include "high/high.h"  // a back-arrow: low does not depend on high
