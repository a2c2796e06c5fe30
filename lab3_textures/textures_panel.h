// textures_panel.h — lab 3's "Textures" window (UI only): per material its maps, sampler and
// sampling mode; the mip-level view; the frame time beside them, and the texture warnings.
// Returns true when a change needs new images, samplers, descriptor sets or pipelines (main
// then rebuilds the renderer); uv scale / offset, emissive strength and the distortion numbers
// are uniforms and change live. A reload of the scene file replaces these edits.
#pragma once

#include "lights.h"

#include <string>
#include <vector>

bool textures_panel(Lighting& lighting, const std::vector<std::string>& warnings, const std::string& auto_choice,
                    float frame_ms);
