#include "cli/json_output.h"

#include <cassert>

#include "google/protobuf/util/json_util.h"

namespace kerf::cli {

std::string FormatProtoJson(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  std::string json;
  [[maybe_unused]] const auto status =
      google::protobuf::util::MessageToJsonString(message, &json, options);
  assert(status.ok());
  return json;
}

}  // namespace kerf::cli
