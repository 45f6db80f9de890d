# The CLI depends on the backend, which alone may include Vulkan's headers.
set(MODULES vulkan backend cli)
set(vulkan_DEPS)
set(backend_DEPS vulkan)
set(cli_DEPS backend)
set(VULKAN_MODULES vulkan backend)
