M98 P"m.g" T0
if exists(param.T)
  M563 P{param.T} D0
ÿvar t = param.T
M563 P{var.t} S"x" H1
G10 P{var.t} X1
while iterations < 2
  T{var.t}
