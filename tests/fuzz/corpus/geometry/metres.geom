units m rad
sonar 0.1 0 0
max_range 3
