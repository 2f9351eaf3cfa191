// The household catalogue of "what to look for next" (evidence.hpp, item 3): common objects and sizes from the
// documentation's tables, each entry citing its row. Rocking entries: the household objects of the real-record
// recovery test (docs/verification.md, "Recovery on real records": "a lamp 8x50 cm, a bottle D6x30, a vase D10x40, a
// speaker 15x60, a clock 10x25, a bookend 10x15, a cabinet 45x180"), with Housner's restitution. Sliding entries: the
// base-on-support pairs of docs/survey.md, "Friction coefficients", at the row's mu range (drawn uniformly per run, as
// a survey's range is). All on a rigid support at amplification 1 (the floor or rigid low furniture on the ground
// floor: docs/survey.md, "Support amplification", first row). docs/survey.md, "What to look for next", lists them.
#include <string>
#include <vector>

#include "topple/inversion/evidence.hpp"

namespace topple {
namespace {

CatalogueObject rocking(std::string name, std::string description, RockingBody body, double w, double h,
                        bool cylinder, std::string source) {
  CatalogueObject c;
  c.name = std::move(name);
  c.description = std::move(description);
  c.object.id = c.name;
  c.object.description = c.description;
  c.object.body = body;
  (cylinder ? c.object.diameter_m : c.object.width_m) = w;
  c.object.height_m = h;
  c.object.mu = {0.4, 0.6};  // not used by the rocking model (no sliding); the wood-stone row's range for the record
  c.object.model = ObjectModel::rock;
  c.object.outcome = Outcome::overturned;
  c.source = std::move(source);
  return c;
}

CatalogueObject sliding(std::string name, std::string description, Interval mu, std::string source) {
  CatalogueObject c;
  c.name = std::move(name);
  c.description = std::move(description);
  c.object.id = c.name;
  c.object.description = c.description;
  c.object.body = RockingBody::block(0.3, 0.1);  // a squat box: the sliding block ignores the body
  c.object.width_m = 0.3;
  c.object.height_m = 0.1;
  c.object.mu = mu;
  c.object.model = ObjectModel::slide;
  c.object.outcome = Outcome::slid;
  c.source = std::move(source);
  return c;
}

std::vector<CatalogueObject> make_catalogue() {
  const std::string rec = "docs/verification.md, \"Recovery on real records\", household objects: ";
  const std::string fr = "docs/survey.md, \"Friction coefficients\", row \"";
  std::vector<CatalogueObject> c;
  c.push_back(rocking("wine bottle", "cylinder, 6 cm across, 30 cm tall", RockingBody::cylinder(0.06, 0.30), 0.06,
                      0.30, true, rec + "a bottle D6x30"));
  c.push_back(rocking("table lamp", "block, 8 cm wide, 50 cm tall", RockingBody::block(0.08, 0.50), 0.08, 0.50, false,
                      rec + "a lamp 8x50 cm"));
  c.push_back(rocking("vase", "cylinder, 10 cm across, 40 cm tall", RockingBody::cylinder(0.10, 0.40), 0.10, 0.40,
                      true, rec + "a vase D10x40"));
  c.push_back(rocking("loudspeaker", "block, 15 cm wide, 60 cm tall", RockingBody::block(0.15, 0.60), 0.15, 0.60,
                      false, rec + "a speaker 15x60"));
  c.push_back(rocking("mantel clock", "block, 10 cm wide, 25 cm tall", RockingBody::block(0.10, 0.25), 0.10, 0.25,
                      false, rec + "a clock 10x25"));
  c.push_back(rocking("bookend", "block, 10 cm wide, 15 cm tall", RockingBody::block(0.10, 0.15), 0.10, 0.15, false,
                      rec + "a bookend 10x15"));
  c.push_back(rocking("tall cabinet", "block, 45 cm deep, 180 cm tall", RockingBody::block(0.45, 1.80), 0.45, 1.80,
                      false, rec + "a cabinet 45x180"));
  c.push_back(sliding("chair on PTFE glides", "furniture on PTFE glides on a hard floor, mu 0.04-0.2", {0.04, 0.2},
                      fr + "PTFE (Teflon) glides on a hard floor | 0.04-0.2\""));
  c.push_back(sliding("felt-padded object", "an object on felt pads on wood, mu 0.2-0.3", {0.2, 0.3},
                      fr + "felt pads on wood | 0.2-0.3\""));
  c.push_back(sliding("wooden box on wood", "a wooden box or tray on a wooden shelf or table, mu 0.25-0.5",
                      {0.25, 0.5}, fr + "wood on wood | 0.25-0.5\""));
  c.push_back(sliding("metal pot on wood", "a metal pot, tin or tool on wood, mu 0.2-0.6", {0.2, 0.6},
                      fr + "metal on wood | 0.2-0.6\""));
  c.push_back(sliding("glass on a glass shelf", "a glass on a clean glass shelf, mu 0.9-1.0", {0.9, 1.0},
                      fr + "glass on glass, clean | 0.9-1.0\""));
  return c;
}

}  // namespace

const std::vector<CatalogueObject>& household_catalogue() {
  static const std::vector<CatalogueObject> catalogue = make_catalogue();
  return catalogue;
}

}  // namespace topple
