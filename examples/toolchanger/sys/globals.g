; globals.g
; shared settings for the tool change, parking and purge macros
; called from config.g; the guards let config.g run again (M98 P"config.g") without errors

if !exists(global.parkX)
  global parkX = -35                 ; left carriage parking position (X)
if !exists(global.parkU)
  global parkU = 335                 ; right carriage parking position (U)
if !exists(global.purgeLength)
  global purgeLength = 12            ; filament pushed through after a long standby (mm)
if !exists(global.wipeSpeed)
  global wipeSpeed = 9000            ; travel speed over the wiper brush (mm/min)
