#include "topple/output/record_fields.hpp"

namespace topple {

const std::array<Field<RecordMetadata>, 8> kRecordMetadataFields{{
    {"format", [](const RecordMetadata& m) -> FieldValue { return m.format; }},
    {"source_file", [](const RecordMetadata& m) -> FieldValue { return m.source_file; }},
    {"event", [](const RecordMetadata& m) -> FieldValue { return m.event; }},
    {"station", [](const RecordMetadata& m) -> FieldValue { return m.station; }},
    {"component", [](const RecordMetadata& m) -> FieldValue { return m.component; }},
    {"azimuth_deg",
     [](const RecordMetadata& m) -> FieldValue { return m.azimuth_deg ? FieldValue(*m.azimuth_deg) : FieldValue{}; }},
    {"vertical", [](const RecordMetadata& m) -> FieldValue { return m.vertical; }},
    {"units_as_read", [](const RecordMetadata& m) -> FieldValue { return m.units_as_read; }},
}};

}  // namespace topple
