; An entry: runs after the boot.
var speed = 3000
if true
  var inner = 1
G1 X0
global late = 1
