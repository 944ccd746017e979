// The gallery report.html leads with when the run wrote one (hsr compare's gallery.json):
// per scene, error against visibility time as a scatter, each point with its fastest to
// slowest run, then the reference and every configuration as a card, its picture beside
// its error map with its figures, its README and the commands that record its steps and
// ask why a pixel came out as it did. A picture opens enlarged, pixels as squares; a click
// on a pixel there names it and gives the hsr why command for it (the page runs nothing).
#pragma once

#include <string>

namespace hsr::studies {

// The gallery's HTML, its data (gallery.json's text) and the script that draws it.
std::string galleryHtml(const std::string& galleryJson);

}  // namespace hsr::studies
