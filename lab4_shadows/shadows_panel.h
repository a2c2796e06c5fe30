// shadows_panel.h — lab 4's "Shadows" window (UI only): per light, casting shadows on / off and
// its map's settings (resolution, fit to view, PCF kernel, filter, biases) with the frame time
// beside them and the texels each map drew (`drawn`);
// the shadow-map view; "animate lights"; how many maps the last frame drew (`renders`: 0 while
// nothing moves, every map while the lights circle; a count that grew every frame would make the
// UI redraw its overlay every frame: imgui_renderer.h); in translucent scenes, what the translucent layers'
// lists could not hold (`translucent_layers`: TranslucentLayers::summary(); empty: no line). A new
// resolution, or a change in which lights cast shadows, needs new images: main sees it
// (Renderer::shadows_match) and rebuilds the renderer.
// A reload of the scene file replaces these edits.
#pragma once

#include "lights.h"

#include <string>

// `drawn`: the texels per side each map drew (ShadowMaps::drawn).
void shadows_panel(Lighting& lighting, float frame_ms, int renders, const std::string& drawn,
                   const std::string& translucent_layers);
