#include "backend/device.h"
#include <vulkan/vulkan.hpp>
