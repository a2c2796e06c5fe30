// Must NOT compile: the Vulkan layer cannot see the app layer (the frame loop is above it).
#include "vk_context.h"
#include "lab_app.h"
