#pragma once
// The offline survey form (`topple survey-form`, docs/survey.md "The offline survey form"): one self-contained HTML
// page (inline CSS and JavaScript; no network, no server) generated from the survey's key table
// (topple/survey/schema.hpp), in which a field team enters a site, its earthquake, the inversion settings and its
// objects, sees the reader's refusals as it types, and saves the survey as TOML and as CSV.
#include <string>

#include <nlohmann/json.hpp>

namespace topple::io {

/// The key table and the friction table as the page reads them: {"keys": [...], "friction": [...]}.
[[nodiscard]] nlohmann::ordered_json survey_schema_json();

/// The whole page.
[[nodiscard]] std::string survey_form_html();

}  // namespace topple::io
