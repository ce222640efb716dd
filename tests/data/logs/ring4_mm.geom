# Four sonars of a test ring, in millimetres and degrees
units mm deg
aperture 25
min_range 100
max_range 6000
sonar 100 0 0
sonar 0 100 90
sonar -100 0 180
sonar 0 -100 -90
