#pragma once
#include <vulkan/vulkan.hpp>
#include "vulkan/context.h"
