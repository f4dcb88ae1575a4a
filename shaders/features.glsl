// The FeatureSet as a specialization constant: a kernel tests `hasFeature(FEATURE_*)`, which the driver
// folds to a constant when the pipeline is built, so the code behind an absent feature is dead and
// removed. Unspecialized pipelines (the default value) keep every feature.
#ifndef RIPPLE_FEATURES_GLSL
#define RIPPLE_FEATURES_GLSL
#include "shared/features.h"

layout(constant_id = 1) const uint FEATURES = 0xFFFFFFFFu;

// A macro, not a function, so the test is itself a specialization constant expression.
#define hasFeature(bit) ((FEATURES & (bit)) != 0u)

#endif
