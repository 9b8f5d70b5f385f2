#include "contactqp/errors.hpp"

namespace contactqp {

InputError::InputError(std::string field, const std::string& message)
    : std::runtime_error(field + " " + message), field_(std::move(field)) {}

}  // namespace contactqp
