(define (problem lander-03)
  (:domain lander)
  (:init
    (flying)
    (= (h) 408.1) (= (v) -15)
    (= (mass) 1081) (= (fuel) 81) (= (burn-rate) 5)
    (= (gravity) 1.62) (= (thrust) 4903.4)
    (= (touch-height) 3) (= (safe-speed) 2))
  (:goal (and (landed))))
