M591 D0 P1 C3S1   ; a control byte in an unquoted pin name: quoting it would not make a string
