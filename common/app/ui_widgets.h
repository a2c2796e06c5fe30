// ui_widgets.h — small ImGui helpers the labs' panels share (UI only: no lesson in them).
#pragma once

#include <imgui.h>

#include <cstdio>
#include <string>

namespace lab::ui {

// A combo box over an enum whose values are 0, 1, …, count − 1 in the order of `items`.
// True when the user picked another value.
template <typename Enum>
bool enum_combo(const char* label, Enum& value, const char* const* items, int count) {
    int v = int(value);
    if (!ImGui::Combo(label, &v, items, count)) return false;
    value = Enum(v);
    return true;
}

// A text field that changes `text` only when the user presses Enter (not at every keystroke).
inline bool edit_on_enter(const char* label, std::string& text) {
    char buffer[512];
    std::snprintf(buffer, sizeof buffer, "%s", text.c_str());
    if (!ImGui::InputText(label, buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue)) return false;
    text = buffer;
    return true;
}

}  // namespace lab::ui
