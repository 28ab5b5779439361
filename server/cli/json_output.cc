#include "cli/json_output.h"

#include "base/check.h"
#include "google/protobuf/util/json_util.h"

namespace kerf::cli {

std::string FormatProtoJson(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  std::string json;
  const auto status = google::protobuf::util::MessageToJsonString(message, &json, options);
  KERF_CHECK(status.ok());
  return json;
}

}  // namespace kerf::cli
