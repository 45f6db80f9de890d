#pragma once
#include <vulkan/vulkan.hpp>
