; A value glued to a command word ('g10-report-only' is the command G10 followed by '-'): RRF120 reports only values
; after a blank, in its full check as in its quick test (may_hold_stray_value). The two disagreed here until the full
; check learnt the rule's scope; the prefilters-off run of fuzz_lint and fuzz_card, which skips the quick test, keeps
; them in step.
M584 X0 Y1 Z2 E3:4
M563 P0 D0
G10 P0
M563 Pct: g10-report-only
G10 P1 X20 Y8 Z0
