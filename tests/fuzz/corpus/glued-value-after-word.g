; RRF120's quick test and its full check disagree here: the full check reports the '-' glued to 'g10' on the
; M563 line, the quick test (every normal run) does not. A seed for when the quick test stands aside under
; no_prefilters again (0122f0b, reverted in da1208e): the prefilters-off run of fuzz_lint and fuzz_card must agree.
M584 X0 Y1 Z2 E3:4
M563 P0 D0
G10 P0
M563 Pct: g10-report-only
G10 P1 X20 Y8 Z0
