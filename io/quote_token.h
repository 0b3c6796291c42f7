// QuoteToken moved to kinematics/quote_token.h (issue 15: kinematics/ and problems/ quote
// names too); this forwarding header keeps existing includes working.
#ifndef MOCAPSOLVE_IO_QUOTE_TOKEN_H_
#define MOCAPSOLVE_IO_QUOTE_TOKEN_H_

#include "kinematics/quote_token.h"

#endif  // MOCAPSOLVE_IO_QUOTE_TOKEN_H_
