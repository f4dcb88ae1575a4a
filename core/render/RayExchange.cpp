// Names of the exchange kinds (see RayExchange.h).
#include "core/render/RayExchange.h"

namespace ripple::core {

const char* exchangeKindName(ExchangeKind kind) {
    switch (kind) {
    case ExchangeKind::Bounds: return "bounds";
    case ExchangeKind::Ring: return "ring";
    }
    return "unknown";
}

std::optional<ExchangeKind> parseExchangeKind(std::string_view name) {
    for (ExchangeKind kind : {ExchangeKind::Bounds, ExchangeKind::Ring})
        if (name == exchangeKindName(kind)) return kind;
    return std::nullopt;
}

}  // namespace ripple::core
