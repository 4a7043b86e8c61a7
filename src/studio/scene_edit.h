// The shots panel's edits of the scene file, made on its text so that the
// file keeps its keys in their order and everything else as it was (re-indented by two).
//
//   swap:  the values of two keys of environment.shots trade places (each file keeps its turn
//          and field of view: they belong to how that file was taken);
//   turn:  a shot's rotate_deg grows by a quarter turn (clockwise); a shot given as a file name or
//          a list of brackets becomes an object to hold it ({"file" | "files", "rotate_deg"});
//   faced: the wall faced when shooting ceiling and floor;
// and the points panel's references of known albedo (a white sheet, a grey card):
//   add_reference:    appends {"polygon_px", "albedo"} to the scene's "references";
//   remove_reference: removes references[index] (and "references" when it is left empty).
// Each throws InputError naming `file` and the JSON path when the scene has no such shot.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace insitu {

std::string swap_shots(const std::string& text, const std::string& file, const std::string& key_a,
                       const std::string& key_b);
std::string turn_shot(const std::string& text, const std::string& file, const std::string& key, int by_deg);
std::string set_faced_wall(const std::string& text, const std::string& file, const std::string& wall);
// `reference` is the page's {"polygon_px", "albedo"}, checked by the scene reader afterwards.
std::string add_reference(const std::string& text, const std::string& file, const nlohmann::json& reference);
std::string remove_reference(const std::string& text, const std::string& file, int index);

}  // namespace insitu
