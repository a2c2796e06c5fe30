// Must NOT compile: the content layer (plain C++) cannot see the Vulkan layer's headers.
#include "scene.h"
#include "vk_context.h"
