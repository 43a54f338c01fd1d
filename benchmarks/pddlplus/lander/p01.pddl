(define (problem lander-01)
  (:domain lander)
  (:init
    (flying)
    (= (h) 112.2) (= (v) -5)
    (= (mass) 1043.98) (= (fuel) 43.98) (= (burn-rate) 5)
    (= (gravity) 1.62) (= (thrust) 5073.7)
    (= (touch-height) 5) (= (safe-speed) 3))
  (:goal (and (landed))))
